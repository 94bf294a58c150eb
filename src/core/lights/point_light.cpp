// The point light and the spot: incidence, power, photons, and the spot's cone.
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
  if (light.isSpot()) in.radiance *= spotFalloff(light, -in.wi);
  in.point = light.position;
  in.margin = in.distance * kShadowRayShortening;
  in.valid = true;
  return in;
}

Color PointLight::power(const Light& light, const SceneSphere&) {
  if (light.isSpot()) return light.radiance() * spotSolidAngle(light);
  return light.radiance() * (4.0f * kPi);
}

PhotonRay PointLight::photon(const Light& light, const SceneSphere&, float u1, float u2, float, float) {
  PhotonRay r;
  if (light.isSpot()) {
    // Uniform within the outer cone, weighted by the falloff over its mean there.
    const float cosT = 1.0f - u1 * (1.0f - light.spotCosOuter);
    const float sinT = std::sqrt(std::max(0.0f, 1.0f - cosT * cosT)), phi = 2.0f * kPi * u2;
    r.origin = light.position;
    r.dir = toWorld(Vec3(sinT * std::cos(phi), sinT * std::sin(phi), cosT), light.direction);
    r.weight = Color(spotFalloff(light, r.dir) * (2.0f * kPi * (1.0f - light.spotCosOuter)) / spotSolidAngle(light));
    return r;
  }
  r.origin = light.position;
  r.dir = uniformSphere(u1, u2);
  return r;
}

float PointLight::classicWeight(const Light& light) {
  if (light.isSpot()) return luminance(light.radiance()) * spotSolidAngle(light) / (4.0f * kPi);
  return luminance(light.radiance());
}

Color PointLight::classicPower(const Light& light, const SceneSphere& bounds, float count) {
  if (light.isSpot()) return LightDefaults::classicPower(light, bounds, count);
  return light.radiance() * (4.0f * kPi / count);  // 4 pi I / count, as always
}

// A point light draws its direction from two numbers, as it always has; a spot draws four.
int PointLight::startNumbers(const Light& light) { return light.isSpot() ? 4 : 2; }

// A rounding error along the photon's way (measured against the light's coordinates and
// the scene's size). A light lying in a surface would otherwise meet that surface at
// t = 0 with every photon, as Embree's watertight test counts such hits, and the gate
// would call everything around it shadowed.
Vec3 PointLight::photonOrigin(const Light& light, const PhotonRay& r, const SceneSphere& bounds) {
  return light.position + r.dir * (gammaBound(7) * (maxComponent(glm::abs(light.position)) + bounds.radius));
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
  light.spotCosOuter = std::cos(outerAngle);
  // A cone with no ramp (inner = outer) would divide by zero in the falloff.
  light.spotCosInner = std::max(std::cos(innerAngle), light.spotCosOuter + 1e-6f);
}

float spotSolidAngle(const Light& light) {
  if (!light.isSpot()) return 4.0f * kPi;
  // 2 pi [ (1 - cos_i) + the ramp's t^2 integrated over cos from cos_o to cos_i ].
  return 2.0f * kPi * ((1.0f - light.spotCosInner) + (light.spotCosInner - light.spotCosOuter) / 3.0f);
}

}  // namespace penumbra
