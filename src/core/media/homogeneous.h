// Closed forms for a homogeneous medium along a ray: Beer–Lambert transmittance,
// free-flight distances, and equiangular distances towards a point (Kulla & Fajardo 2012).
#pragma once
#include "core/math.h"
#include <algorithm>
#include <cmath>

namespace penumbra {

// exp(-sigmaT d) per channel; 0 where sigmaT is infinite, 1 over no distance.
inline Color transmittance(const Color& sigmaT, float d) {
  if (!(d > 0.0f)) return Color(1.0f);
  return glm::exp(-glm::min(sigmaT * d, Color(1e30f)));
}

// A free-flight distance drawn with density s exp(-s t) (s > 0); may exceed the segment.
inline float sampleFreeFlight(float s, float u) { return -std::log1p(-std::min(u, 0.99999994f)) / s; }

// A distance in [a, b] along a ray (origin o, unit dir d) with density proportional to
// 1 / |x(t) - p|^2: uniform in the angle subtended at p.
struct EquiangularSample {
  float t = 0.0f;
  float pdf = 0.0f;  // per unit length
};
inline float equiangularPdf(float delta, float dist, float thetaA, float thetaB, float t) {
  const float x = t - delta;
  return dist / ((thetaB - thetaA) * (dist * dist + x * x));
}
inline EquiangularSample sampleEquiangular(const Vec3& o, const Vec3& d, const Vec3& p, float a, float b, float u) {
  const float delta = glm::dot(p - o, d);
  const float dist = std::max(glm::length(o + delta * d - p), 1e-7f);
  const float thetaA = std::atan2(a - delta, dist), thetaB = std::atan2(b - delta, dist);
  if (!(thetaB > thetaA)) return {a, 0.0f};
  const float t = std::clamp(delta + dist * std::tan(thetaA + u * (thetaB - thetaA)), a, b);
  return {t, equiangularPdf(delta, dist, thetaA, thetaB, t)};
}

}  // namespace penumbra
