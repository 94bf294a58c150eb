// The environment light's list entry, forwarding to core/lights/environment_map.h.
#include "core/lights/environment_map.h"

namespace penumbra {

LightIncidence EnvironmentLight::sample(const LightSampler& s, float u1, float u2) {
  const Light& light = *s.light;
  LightIncidence in;
  const EnvironmentSample e = sampleEnvironmentSphere(light, u1, u2);
  in.wi = e.wi;
  in.radiance = e.valid ? e.radiance / e.pdf : Color(0.0f);
  in.valid = e.valid;
  return in;
}

Color EnvironmentLight::power(const Light& light, const SceneSphere& bounds) { return environmentPower(light, bounds); }

PhotonRay EnvironmentLight::photon(const Light& light, const SceneSphere& bounds, float u1, float u2, float u3,
                                   float u4) {
  return environmentPhoton(light, bounds, u1, u2, u3, u4);
}

// The classic model lights by it through shadow rays only.
float EnvironmentLight::classicWeight(const Light&) { return 0.0f; }

}  // namespace penumbra
