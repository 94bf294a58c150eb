// Direction sampling from two uniform numbers in [0,1). Mapped analytically
// (no rejection), so every photon consumes a fixed number of random values.
#pragma once
#include "core/math.h"
#include "core/rng.h"
#include <numeric>

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

// Point s of n in the unit square, jittered within its stratum. A perfect square n
// uses a sqrt(n) x sqrt(n) grid; any other n a rank-1 lattice (x stratum s, y
// stratum s * g mod n with g coprime to n), so every row and column gets one point.
inline Vec2 stratified2D(int s, int n, Rng& rng) {
  if (n == 1) return {0.5f, 0.5f};
  int side = static_cast<int>(std::lround(std::sqrt(static_cast<double>(n))));
  if (side * side == n) {
    return {(s % side + rng.uniform()) / side, (s / side + rng.uniform()) / side};
  }
  int g = std::max(1, static_cast<int>(std::lround(n * 0.618034)));
  while (std::gcd(g, n) != 1) ++g;
  int row = static_cast<int>((static_cast<int64_t>(s) * g) % n);
  return {(s + rng.uniform()) / n, (row + rng.uniform()) / n};
}

}  // namespace penumbra
