// The sphere light: its cone from a shading point, uniform samples over the cone,
// the closed form above both horizons, area and photons.
#include "core/light_sample.h"
#include "core/light_strata.h"
#include "core/sampling.h"
#include <algorithm>

namespace penumbra {

void SphereLight::prepare(const Light& light, const Vec3& p, LightSampler& s) {
  const Vec3 toCentre = light.position - p;
  s.dc2 = glm::dot(toCentre, toCentre);
  s.r2 = light.radius * light.radius;
  s.outside = s.dc2 > s.r2 && std::isfinite(s.dc2);
  if (s.outside) {
    s.dc = std::sqrt(s.dc2);
    s.w = toCentre / s.dc;
    // 1 - cos(theta_max) as sin^2 / (1 + cos): the subtraction would cancel to 0
    // for a small or distant sphere (r / d below ~2e-4 in float).
    const float sin2Max = s.r2 / s.dc2;
    s.oneMinusCosMax = sin2Max / (1.0f + std::sqrt(std::max(0.0f, 1.0f - sin2Max)));
    orthonormalBasis(s.w, s.t, s.b);
  }
}

LightIncidence SphereLight::sample(const LightSampler& s, float u1, float u2) {
  LightIncidence in;
  if (!s.outside) return in;  // inside (or on) the sphere
  // Uniform over the cone: 1 - cos(theta) uniform in [0, 1 - cos(theta_max)].
  const float t = u1 * s.oneMinusCosMax;
  const float cosTheta = 1.0f - t, sinTheta = std::sqrt(std::max(0.0f, t * (2.0f - t)));
  const float phi = 2.0f * kPi * u2;
  in.wi = cosTheta * s.w + sinTheta * (std::cos(phi) * s.t + std::sin(phi) * s.b);
  // The near intersection along wi: dc cos - sqrt(r^2 - dc^2 sin^2), never < 0.
  const float disc = std::max(0.0f, s.r2 - s.dc2 * sinTheta * sinTheta);
  in.distance = std::max(0.0f, s.dc * cosTheta - std::sqrt(disc));
  in.radiance = s.light->radiance() * (2.0f * kPi * s.oneMinusCosMax);
  // Shadow rays to a sphere light identify the emitter they meet: no margin needed.
  in.point = s.p + in.distance * in.wi;
  in.margin = -in.distance * kShadowRayShortening;
  in.valid = in.distance > 0.0f;
  return in;
}

bool SphereLight::irradiance(const LightSampler& s, const Vec3& n, const Vec3& ng, Color& E) {
  const Light& light = *s.light;
  if (!s.outside) return false;
  const float cosBeta = glm::dot(n, s.w), cosGeo = glm::dot(ng, s.w), sin2Alpha = s.r2 / s.dc2;
  // Cut by either horizon: no closed form.
  if (cosBeta <= 0.0f || cosBeta * cosBeta < sin2Alpha || cosGeo <= 0.0f || cosGeo * cosGeo < sin2Alpha)
    return false;
  E = light.radiance() * (kPi * sin2Alpha * cosBeta);
  return true;
}

float SphereLight::area(const Light& light) { return 4.0f * kPi * light.radius * light.radius; }

PhotonRay SphereLight::photon(const Light& light, const SceneSphere&, float u1, float u2, float u3, float u4) {
  PhotonRay r = start(light, uniformSphere(u1, u2));
  r.stratum = sphereStratum(r.normal);
  r.dir = toWorld(cosineHemisphere(u3, u4), r.normal);
  return r;
}

PhotonRay SphereLight::start(const Light& light, const Vec3& n) {
  PhotonRay r;
  r.origin = light.position + light.radius * n;
  r.normal = n;
  r.error = gammaBound(5) * (maxComponent(glm::abs(light.position)) + light.radius);
  return r;
}

EmitterShape SphereLight::emitter(const Light& light) {
  EmitterShape e;
  e.sphere = Sphere{light.position, light.radius, 0};
  e.twoSided = true;
  return e;
}

}  // namespace penumbra
