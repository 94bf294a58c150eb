// The quad light: a one-sided Lambertian parallelogram (position, edge1, edge2),
// sampled uniformly by area. Included by core/light_types.h only.
#pragma once

namespace penumbra {

struct QuadLight : LightDefaults {
  static constexpr LightType kType = LightType::Quad;
  static constexpr LightTraits kTraits = {
      LightSupport::Area, StrataKind::Parametric, AimKind::Surface,
      ShadowTest::Segment, DirectSampling::Gated,
      /*emitsShadowPhotons*/ true, /*opensPhysicalMaps*/ true};
  static void prepare(const Light& light, const Vec3& p, LightSampler& s);
  static LightIncidence sample(const LightSampler& s, float u1, float u2);
  static bool irradiance(const LightSampler& s, const Vec3& n, const Vec3& ng, Color& E);
  static float area(const Light& light);
  static PhotonRay photon(const Light& light, const SceneSphere& bounds, float u1, float u2, float u3, float u4);
};

}  // namespace penumbra
