// The directional light: incidence, power over the scene's disc, photons from it.
#include "core/light_sample.h"
#include "core/sampling.h"

namespace penumbra {

LightIncidence DirectionalLight::sample(const LightSampler& s, float, float) {
  const Light& light = *s.light;
  LightIncidence in;
  in.wi = -light.direction;
  in.radiance = light.radiance();
  in.valid = true;
  return in;
}

Color DirectionalLight::power(const Light& light, const SceneSphere& bounds) {
  return light.radiance() * (kPi * bounds.radius * bounds.radius);
}

PhotonRay DirectionalLight::photon(const Light& light, const SceneSphere& bounds, float, float, float u3, float u4) {
  PhotonRay r;
  // Uniform over the disc that covers the scene, seen along the light's direction,
  // placed just outside the bounding sphere.
  float rad = bounds.radius * std::sqrt(u3), phi = 2.0f * kPi * u4;
  Vec3 t, b;
  orthonormalBasis(light.direction, t, b);
  r.origin = bounds.center - light.direction * (SceneSphere::kSkyStart * bounds.radius) +
             rad * (std::cos(phi) * t + std::sin(phi) * b);
  r.dir = light.direction;
  return r;
}

Vec3 DirectionalLight::photonOrigin(const Light&, const PhotonRay& r, const SceneSphere&) { return r.origin; }

// The classic model lights by it through shadow rays only.
float DirectionalLight::classicWeight(const Light&) { return 0.0f; }

Light makeDirectionalLight(const Vec3& direction) {
  Light light;
  light.type = LightType::Directional;
  light.direction = direction;
  return light;
}

}  // namespace penumbra
