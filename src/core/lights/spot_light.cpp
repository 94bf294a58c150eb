// The spot: a point light's incidence and origin under its cone, its power, photons
// within the outer cone, and the cone itself.
#include "core/light_sample.h"
#include "core/sampling.h"
#include <algorithm>

namespace penumbra {

LightIncidence SpotLight::sample(const LightSampler& s, float u1, float u2) {
  LightIncidence in = PointLight::sample(s, u1, u2);
  if (in.valid) in.radiance *= spotFalloff(*s.light, -in.wi);
  return in;
}

Color SpotLight::power(const Light& light, const SceneSphere&) { return light.radiance() * spotSolidAngle(light); }

PhotonRay SpotLight::photon(const Light& light, const SceneSphere&, float u1, float u2, float, float) {
  PhotonRay r;
  // Uniform within the outer cone, weighted by the falloff over its mean there.
  const float cosT = 1.0f - u1 * (1.0f - light.spotCosOuter);
  const float sinT = std::sqrt(std::max(0.0f, 1.0f - cosT * cosT)), phi = 2.0f * kPi * u2;
  r.origin = light.position;
  r.dir = toWorld(Vec3(sinT * std::cos(phi), sinT * std::sin(phi), cosT), light.direction);
  r.weight = Color(spotFalloff(light, r.dir) * (2.0f * kPi * (1.0f - light.spotCosOuter)) / spotSolidAngle(light));
  return r;
}

float SpotLight::classicWeight(const Light& light) {
  return luminance(light.radiance()) * spotSolidAngle(light) / (4.0f * kPi);
}

Vec3 SpotLight::photonOrigin(const Light& light, const PhotonRay& r, const SceneSphere& bounds) {
  return PointLight::photonOrigin(light, r, bounds);
}

float spotFalloff(const Light& light, const Vec3& dir) {
  if (!light.isSpot()) return 1.0f;
  const float c = glm::dot(dir, light.direction);
  if (c >= light.spotCosInner) return 1.0f;
  if (c <= light.spotCosOuter) return 0.0f;
  const float t = (c - light.spotCosOuter) / (light.spotCosInner - light.spotCosOuter);
  return t * t;
}

void setSpotCone(Light& light, float innerAngle, float outerAngle) {
  light.type = LightType::Spot;
  light.spotCosOuter = std::cos(outerAngle);
  // A cone with no ramp (inner = outer) would divide by zero in the falloff.
  light.spotCosInner = std::max(std::cos(innerAngle), light.spotCosOuter + 1e-6f);
}

float spotSolidAngle(const Light& light) {
  if (!light.isSpot()) return 4.0f * kPi;
  // 2 pi [ (1 - cos_i) + the ramp's t^2 integrated over cos from cos_o to cos_i ].
  return 2.0f * kPi * ((1.0f - light.spotCosInner) + (light.spotCosInner - light.spotCosOuter) / 3.0f);
}

Light makeSpotLight(const Vec3& position, const Vec3& direction, float innerAngle, float outerAngle) {
  Light light;
  light.position = position;
  light.direction = direction;
  setSpotCone(light, innerAngle, outerAngle);
  return light;
}

}  // namespace penumbra
