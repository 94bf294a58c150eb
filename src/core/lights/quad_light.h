// The quad light: a one-sided Lambertian parallelogram (position, edge1, edge2),
// sampled uniformly by area. Included by core/light_types.h only.
#pragma once

namespace penumbra {

struct QuadLight : LightDefaults {
  static constexpr LightType kType = LightType::Quad;
  static constexpr LightTraits kTraits = {
      LightSupport::Area, StrataKind::Parametric, AimKind::Surface,
      ShadowTest::Segment, DirectSampling::Gated,
      /*emitsShadowPhotons*/ true, /*opensPhysicalMaps*/ true,
      /*gateAvoidsRays*/ true, "quad", kLambertianPower};
  static void prepare(const Light& light, const Vec3& p, LightSampler& s);
  static LightIncidence sample(const LightSampler& s, float u1, float u2);
  static bool irradiance(const LightSampler& s, const Vec3& n, const Vec3& ng, Color& E);
  static float area(const Light& light);
  static PhotonRay photon(const Light& light, const SceneSphere& bounds, float u1, float u2, float u3, float u4);
  static EmitterShape emitter(const Light& light);  // makeQuad's two triangles, one-sided
};

// Parallelogram corner, corner+edge1, corner+edge1+edge2, corner+edge2 as two
// triangles wound so the geometric normal is normalize(cross(edge1, edge2));
// that normal is also stored per vertex, and uvs run (0,0) (1,0) (1,1) (0,1).
// The edges must be non-zero and not parallel (the caller checks). The quad light's
// surface, and the scene format's quad object.
TriangleMesh makeQuad(const Vec3& corner, const Vec3& edge1, const Vec3& edge2, int material = 0);

}  // namespace penumbra
