// Direction sampling from two uniform numbers in [0,1). Mapped analytically
// (no rejection), so every photon consumes a fixed number of random values.
#pragma once
#include "core/math.h"

namespace penumbra {

// Uniform over the unit sphere: z uniform in [-1,1], phi uniform (Archimedes).
inline Vec3 uniformSphere(float u1, float u2) {
  float z = 1.0f - 2.0f * u1;
  float r = std::sqrt(std::max(0.0f, 1.0f - z * z));
  float phi = 2.0f * kPi * u2;
  return {r * std::cos(phi), r * std::sin(phi), z};
}

// Uniform over the hemisphere around +z; pdf 1 / (2 pi).
inline Vec3 uniformHemisphere(float u1, float u2) {
  float z = u1;
  float r = std::sqrt(std::max(0.0f, 1.0f - z * z));
  float phi = 2.0f * kPi * u2;
  return {r * std::cos(phi), r * std::sin(phi), z};
}

// Cosine-weighted over the hemisphere around +z (Malley); pdf cos(theta) / pi.
inline Vec3 cosineHemisphere(float u1, float u2) {
  float r = std::sqrt(u1);
  float phi = 2.0f * kPi * u2;
  return {r * std::cos(phi), r * std::sin(phi), std::sqrt(std::max(0.0f, 1.0f - u1))};
}

// Expresses a +z-frame direction in the frame whose z axis is unit vector n.
inline Vec3 toWorld(const Vec3& local, const Vec3& n) {
  Vec3 t, b;
  orthonormalBasis(n, t, b);
  return local.x * t + local.y * b + local.z * n;
}

}  // namespace penumbra
