// The directional light: irradiance along one direction, its photons from a disc
// covering the scene. Included by core/light_types.h only.
#pragma once

namespace penumbra {

struct DirectionalLight : LightDefaults {
  static constexpr LightType kType = LightType::Directional;
  static constexpr LightTraits kTraits = {
      LightSupport::Direction, StrataKind::One, AimKind::Disc,
      ShadowTest::Segment, DirectSampling::Gated,
      /*emitsShadowPhotons*/ false, /*opensPhysicalMaps*/ false,
      /*gateAvoidsRays*/ true, "directional", "pi R^2 x color x intensity over the scene's bounding disc"};
  static LightIncidence sample(const LightSampler& s, float u1, float u2);
  static Color power(const Light& light, const SceneSphere& bounds);
  static PhotonRay photon(const Light& light, const SceneSphere& bounds, float u1, float u2, float u3, float u4);
  static float classicWeight(const Light& light);
  // As drawn: outside the scene's bounding sphere already.
  static Vec3 photonOrigin(const Light& light, const PhotonRay& r, const SceneSphere& bounds);
};

}  // namespace penumbra
