// The spot: a point light aimed along `direction` with glTF's cone, full intensity within
// the inner angle, falling to 0 at the outer (spotFalloff). Included by core/light_types.h only.
#pragma once

namespace penumbra {

// Its cone would cut the caustic aim's cones: no aim.
struct SpotLight : LightDefaults {
  static constexpr LightType kType = LightType::Spot;
  static constexpr LightTraits kTraits = {
      LightSupport::Position, StrataKind::One, AimKind::None,
      ShadowTest::Segment, DirectSampling::Gated,
      /*emitsShadowPhotons*/ true, /*opensPhysicalMaps*/ true,
      /*gateAvoidsRays*/ true, "spot", "4 pi x color x intensity"};
  static LightIncidence sample(const LightSampler& s, float u1, float u2);
  static Color power(const Light& light, const SceneSphere& bounds);
  static PhotonRay photon(const Light& light, const SceneSphere& bounds, float u1, float u2, float u3, float u4);
  static float classicWeight(const Light& light);
  // As a point light's (photonOrigin in point_light.cpp says why).
  static Vec3 photonOrigin(const Light& light, const PhotonRay& r, const SceneSphere& bounds);
};

}  // namespace penumbra
