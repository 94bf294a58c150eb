// The point light: incidence, power, photons (uniform over the sphere) and their origin.
#include "core/light_sample.h"
#include "core/sampling.h"
#include <algorithm>

namespace penumbra {

LightIncidence PointLight::sample(const LightSampler& s, float, float) {
  const Light& light = *s.light;
  LightIncidence in;
  Vec3 d = light.position - s.p;
  float d2 = glm::dot(d, d);
  if (!(d2 > 0.0f) || !std::isfinite(d2)) return in;
  in.distance = std::sqrt(d2);
  in.wi = d / in.distance;
  in.radiance = light.radiance() * (1.0f / d2);  // as the Whitted tracer always did: bit-identical images
  in.point = light.position;
  in.margin = in.distance * kShadowRayShortening;
  in.valid = true;
  return in;
}

Color PointLight::power(const Light& light, const SceneSphere&) {
  return light.radiance() * (4.0f * kPi);
}

PhotonRay PointLight::photon(const Light& light, const SceneSphere&, float u1, float u2, float, float) {
  PhotonRay r;
  r.origin = light.position;
  r.dir = uniformSphere(u1, u2);
  return r;
}

float PointLight::classicWeight(const Light& light) {
  return luminance(light.radiance());
}

Color PointLight::classicPower(const Light& light, const SceneSphere&, float count) {
  return light.radiance() * (4.0f * kPi / count);  // 4 pi I / count, as always
}

// A point light draws its direction from two numbers, as it always has.
int PointLight::startNumbers(const Light&) { return 2; }

// A rounding error along the photon's way (measured against the light's coordinates and
// the scene's size). A light lying in a surface would otherwise meet that surface at
// t = 0 with every photon, as Embree's watertight test counts such hits, and the gate
// would call everything around it shadowed.
Vec3 PointLight::photonOrigin(const Light& light, const PhotonRay& r, const SceneSphere& bounds) {
  return light.position + r.dir * (gammaBound(7) * (maxComponent(glm::abs(light.position)) + bounds.radius));
}

Light makePointLight(const Vec3& position) {
  Light light;
  light.type = LightType::Point;
  light.position = position;
  return light;
}

}  // namespace penumbra
