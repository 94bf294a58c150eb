// The point light: radiant intensity from one position, the same every way. Included by core/light_types.h only.
#pragma once

namespace penumbra {

struct PointLight : LightDefaults {
  static constexpr LightType kType = LightType::Point;
  static constexpr LightTraits kTraits = {
      LightSupport::Position, StrataKind::One, AimKind::Cone,
      ShadowTest::Segment, DirectSampling::Gated,
      /*emitsShadowPhotons*/ true, /*opensPhysicalMaps*/ true,
      /*gateAvoidsRays*/ true, "point", "4 pi x color x intensity"};
  static LightIncidence sample(const LightSampler& s, float u1, float u2);
  static Color power(const Light& light, const SceneSphere& bounds);
  static PhotonRay photon(const Light& light, const SceneSphere& bounds, float u1, float u2, float u3, float u4);
  static float classicWeight(const Light& light);
  static Color classicPower(const Light& light, const SceneSphere& bounds, float count);
  static int startNumbers(const Light& light);  // 2
  // Its position, a rounding error along the way (photonOrigin in point_light.cpp says why).
  static Vec3 photonOrigin(const Light& light, const PhotonRay& r, const SceneSphere& bounds);
};

}  // namespace penumbra
