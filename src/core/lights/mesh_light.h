// The mesh light's entry in the light list; its code (construction, sampling by area,
// the closed form, photons) is core/lights/emissive_mesh.cpp. Included by core/light_types.h only.
#pragma once

namespace penumbra {

// A mesh light's triangles were picked by one number, so its (u, v) cells are not
// regions of it: one stratum.
struct MeshLight : LightDefaults {
  static constexpr LightType kType = LightType::Mesh;
  static constexpr LightTraits kTraits = {
      LightSupport::Area, StrataKind::One, AimKind::Surface,
      ShadowTest::Segment, DirectSampling::Gated,
      /*emitsShadowPhotons*/ true, /*opensPhysicalMaps*/ true,
      /*gateAvoidsRays*/ false, nullptr, kLambertianPower};
  static void prepare(const Light& light, const Vec3& p, LightSampler& s);
  // One sample uniform by area (pdf_A = 1 / A; textured: by area x luminance): the
  // incidence L cos_l / (pdf_A d^2), invalid behind the sampled triangle's emitting side
  // (a two-sided light has none).
  static LightIncidence sample(const LightSampler& s, float u1, float u2);
  // Lambert's formula per triangle facing p, each clipped to the hemispheres of n and
  // ng. False above kMeshClosedFormTriangles triangles (sample instead: the cost would
  // grow with the mesh) and for a textured light.
  static bool irradiance(const LightSampler& s, const Vec3& n, const Vec3& ng, Color& E);
  static float area(const Light& light);
  static Color power(const Light& light, const SceneSphere& bounds);
  // A photon from a uniform point (triangle by area, or area x luminance, from u1,
  // position from u1's remainder and u2) in a cosine-weighted direction about that
  // triangle's normal (or, two-sided, either side's); a textured light's photon weighs
  // its texel over the triangle's density.
  static PhotonRay photon(const Light& light, const SceneSphere& bounds, float u1, float u2, float u3, float u4);
  static float classicWeight(const Light& light);
  static size_t sampleTable(const Light& light);  // its cumulative areas
};

}  // namespace penumbra
