// Reflection, Snell refraction and unpolarised Fresnel. Shared by the tracer and
// the photon pass, so photons and camera rays bend identically (how often a photon
// refracts is its material's p_t, not Fresnel: see docs/photon-maps.md).
#pragma once
#include "core/math.h"

namespace penumbra {

// Mirror direction of incident direction d about normal n: R = d - 2 (n.d) n.
inline Vec3 reflect(const Vec3& d, const Vec3& n) { return d - 2.0f * glm::dot(n, d) * n; }

// Refracts unit direction d through a surface with unit normal n facing the
// incident side (dot(d, n) < 0), eta = n_incident / n_transmitted. Returns false
// on total internal reflection, i.e. when sin^2(theta_t) > 1.
inline bool refract(const Vec3& d, const Vec3& n, float eta, Vec3& out) {
  float cosI = -glm::dot(n, d);
  float sin2T = eta * eta * std::max(0.0f, 1.0f - cosI * cosI);
  if (sin2T > 1.0f) return false;
  float cosT = std::sqrt(1.0f - sin2T);
  out = eta * d + (eta * cosI - cosT) * n;
  return true;
}

// Fresnel reflectance for unpolarised light, the mean of the s and p terms.
// cosI is the cosine on the incident side, etaI / etaT the indices either side.
// Returns 1 beyond the critical angle (total internal reflection); kt = 1 - kr.
inline float fresnelDielectric(float cosI, float etaI, float etaT) {
  cosI = std::clamp(cosI, 0.0f, 1.0f);
  float sinT = etaI / etaT * std::sqrt(std::max(0.0f, 1.0f - cosI * cosI));
  if (sinT >= 1.0f) return 1.0f;
  float cosT = std::sqrt(std::max(0.0f, 1.0f - sinT * sinT));
  float rs = (etaI * cosI - etaT * cosT) / (etaI * cosI + etaT * cosT);
  float rp = (etaT * cosI - etaI * cosT) / (etaT * cosI + etaI * cosT);
  return 0.5f * (rs * rs + rp * rp);
}

}  // namespace penumbra
