// The environment light's entry in the light list: forwards to core/lights/environment_map.h,
// which holds its map, sampling and photons. Included by core/light_types.h only.
#pragma once

namespace penumbra {

struct EnvironmentLight : LightDefaults {
  static constexpr LightType kType = LightType::Environment;
  static constexpr LightTraits kTraits = {
      LightSupport::Infinite, StrataKind::One, AimKind::None,
      ShadowTest::Segment, DirectSampling::EnvironmentMis,
      /*emitsShadowPhotons*/ false, /*opensPhysicalMaps*/ true,
      /*gateAvoidsRays*/ false, nullptr, "pi R^2 x the integral of color x intensity (x map) over all directions"};
  // Without a normal: the map by luminance, a constant sky uniformly (the tracers
  // sample it about the normal instead, trace/environment_light.h).
  static LightIncidence sample(const LightSampler& s, float u1, float u2);
  static Color power(const Light& light, const SceneSphere& bounds);
  static PhotonRay photon(const Light& light, const SceneSphere& bounds, float u1, float u2, float u3, float u4);
  static float classicWeight(const Light& light);
};

}  // namespace penumbra
