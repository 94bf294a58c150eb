// The Henyey–Greenstein phase function: its value and an exact sample of it. Both take
// propagation directions: cosTheta = dot(direction before, direction after), so g > 0
// keeps light going forwards.
#pragma once
#include "core/math.h"
#include <algorithm>
#include <cmath>

namespace penumbra {

// p(cosTheta) per steradian; integrates to 1 over the sphere. In double, with
// 1 + g^2 - 2 g cosTheta written as a sum of two non-negative terms: near |g| = 1 the
// plain form cancels to 0 at the lobe's peak (inf, or a lobe that integrates to 0.97).
inline double henyeyGreensteinD(double g, double cosTheta) {
  const double denom = g >= 0.0 ? (1.0 - g) * (1.0 - g) + 2.0 * g * (1.0 - cosTheta)
                                : (1.0 + g) * (1.0 + g) - 2.0 * g * (1.0 + cosTheta);
  return 0.25 / glm::pi<double>() * (1.0 - g) * (1.0 + g) / (denom * std::sqrt(std::max(denom, 1e-300)));
}
inline float henyeyGreenstein(float g, float cosTheta) { return float(henyeyGreensteinD(g, cosTheta)); }

// Below this |g| the phase is isotropic to float precision: samplers and gathers treat
// it as 1 / (4 pi).
inline constexpr float kIsotropicPhaseG = 1e-6f;

struct PhaseSample {
  Vec3 dir;   // the new propagation direction (unit)
  float pdf;  // equals henyeyGreenstein(g, dot(before, dir)): the weight p / pdf is 1
};

// Inverts the cosine's CDF (Pharr, Jakob & Humphreys, pbrt-v4 §11.3.1); near g = 0 the
// isotropic formula, whose inversion would divide by g.
inline PhaseSample sampleHenyeyGreenstein(float g, const Vec3& before, float u1, float u2) {
  double cosTheta;
  if (std::abs(g) < kIsotropicPhaseG) {
    cosTheta = 1.0 - 2.0 * u1;
  } else {
    const double gd = g, s = (1.0 - gd * gd) / (1.0 + gd - 2.0 * gd * u1);
    cosTheta = (1.0 + gd * gd - s * s) / (2.0 * gd);
  }
  cosTheta = std::clamp(cosTheta, -1.0, 1.0);
  const float sinTheta = float(std::sqrt(std::max(0.0, (1.0 - cosTheta) * (1.0 + cosTheta))));
  const float phi = 2.0f * kPi * u2;
  Vec3 t, b;
  orthonormalBasis(before, t, b);
  const Vec3 dir = glm::normalize(sinTheta * std::cos(phi) * t + sinTheta * std::sin(phi) * b + float(cosTheta) * before);
  return {dir, float(henyeyGreensteinD(g, cosTheta))};
}

}  // namespace penumbra
