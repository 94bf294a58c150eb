// The Henyey–Greenstein phase function: its value and an exact sample of it. Both take
// propagation directions: cosTheta = dot(direction before, direction after), so g > 0
// keeps light going forwards.
#pragma once
#include "core/math.h"
#include <algorithm>
#include <cmath>

namespace penumbra {

// p(cosTheta) per steradian; integrates to 1 over the sphere.
inline float henyeyGreenstein(float g, float cosTheta) {
  const float denom = 1.0f + g * g - 2.0f * g * cosTheta;
  return 0.25f / kPi * (1.0f - g * g) / (denom * std::sqrt(std::max(denom, 1e-12f)));
}

struct PhaseSample {
  Vec3 dir;   // the new propagation direction (unit)
  float pdf;  // equals henyeyGreenstein(g, dot(before, dir)): the weight p / pdf is 1
};

// Inverts the cosine's CDF (Pharr, Jakob & Humphreys, pbrt-v4 §11.3.1); near g = 0 the
// isotropic formula, whose inversion would divide by g.
inline PhaseSample sampleHenyeyGreenstein(float g, const Vec3& before, float u1, float u2) {
  float cosTheta;
  if (std::abs(g) < 1e-3f) {
    cosTheta = 1.0f - 2.0f * u1;
  } else {
    const float s = (1.0f - g * g) / (1.0f + g - 2.0f * g * u1);
    cosTheta = (1.0f + g * g - s * s) / (2.0f * g);
  }
  cosTheta = std::clamp(cosTheta, -1.0f, 1.0f);
  const float sinTheta = std::sqrt(std::max(0.0f, 1.0f - cosTheta * cosTheta));
  const float phi = 2.0f * kPi * u2;
  Vec3 t, b;
  orthonormalBasis(before, t, b);
  const Vec3 dir = glm::normalize(sinTheta * std::cos(phi) * t + sinTheta * std::sin(phi) * b + cosTheta * before);
  return {dir, henyeyGreenstein(g, cosTheta)};
}

}  // namespace penumbra
