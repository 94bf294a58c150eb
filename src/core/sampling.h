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

// Shirley and Chiu's concentric map of [0,1)^2 onto the unit disc. It preserves area,
// so equal cells of (u1, u2) are equal parts of the disc (a planar light's strata), and
// keeps neighbouring cells neighbours, as a grid of a square's samples expects.
inline Vec2 concentricDisk(float u1, float u2) {
  const float a = 2.0f * u1 - 1.0f, b = 2.0f * u2 - 1.0f;
  if (a == 0.0f && b == 0.0f) return Vec2(0.0f);
  const bool wide = std::fabs(a) > std::fabs(b);
  const float r = wide ? a : b;
  const float phi = wide ? 0.25f * kPi * (b / a) : 0.5f * kPi - 0.25f * kPi * (a / b);
  return Vec2(r * std::cos(phi), r * std::sin(phi));
}

// Expresses a +z-frame direction in the frame whose z axis is unit vector n.
inline Vec3 toWorld(const Vec3& local, const Vec3& n) {
  Vec3 t, b;
  orthonormalBasis(n, t, b);
  return local.x * t + local.y * b + local.z * n;
}

// Point s of n in the unit square, jittered within its stratum. A perfect square n
// uses a sqrt(n) x sqrt(n) grid; any other n a rank-1 lattice (x stratum s, y
// stratum s * g + shift mod n with g coprime to n), so every row and column gets one
// point. The shift is drawn once per set: a fixed lattice covers only n of the n^2
// cells, and each point must be uniform over the square for the set's mean to be
// unbiased. The layout is worked out once per set, not once per point.
class Stratified2D {
 public:
  Stratified2D(int n, Rng& rng) : n_(n) {
    if (n <= 1) return;
    side_ = static_cast<int>(std::lround(std::sqrt(static_cast<double>(n))));
    if (side_ * side_ == n) return;
    side_ = 0;
    g_ = std::max(1, static_cast<int>(std::lround(n * 0.618034)));
    while (std::gcd(g_, n) != 1) ++g_;
    shift_ = static_cast<int>(rng.nextU32() % static_cast<uint32_t>(n));
  }
  Vec2 operator()(int s, Rng& rng) const {
    if (n_ <= 1) return {0.5f, 0.5f};
    if (side_ > 0) return {(s % side_ + rng.uniform()) / side_, (s / side_ + rng.uniform()) / side_};
    const int row = static_cast<int>((static_cast<int64_t>(s) * g_ + shift_) % n_);
    return {(s + rng.uniform()) / n_, (row + rng.uniform()) / n_};
  }

 private:
  int n_, side_ = 0, g_ = 1, shift_ = 0;
};

// Point i of a (0,2)-sequence in base 2 (van der Corput, and Sobol's second
// dimension), each coordinate's bits XORed with half of `scramble` (Kollig & Keller
// 2002): every aligned run of 2^k points, so every prefix of 2^k, puts one point in
// each elementary cell of area 2^-k, and a random scramble makes each point uniform.
inline Vec2 sobol02(uint32_t i, uint64_t scramble) {
  uint32_t x = i;  // bit reversal: the radical inverse in base 2
  x = (x << 16) | (x >> 16);
  x = ((x & 0x00ff00ffu) << 8) | ((x & 0xff00ff00u) >> 8);
  x = ((x & 0x0f0f0f0fu) << 4) | ((x & 0xf0f0f0f0u) >> 4);
  x = ((x & 0x33333333u) << 2) | ((x & 0xccccccccu) >> 2);
  x = ((x & 0x55555555u) << 1) | ((x & 0xaaaaaaaau) >> 1);
  uint32_t y = 0;
  for (uint32_t v = 1u << 31; i != 0; i >>= 1, v ^= v >> 1) {
    if (i & 1u) y ^= v;
  }
  x ^= static_cast<uint32_t>(scramble);
  y ^= static_cast<uint32_t>(scramble >> 32);
  // The top 24 bits: exact in float and below 1.
  return {static_cast<float>(x >> 8) * 0x1p-24f, static_cast<float>(y >> 8) * 0x1p-24f};
}

// Point i of the 4-D Kronecker sequence R_4 (Roberts 2018): frac(shift + i alpha),
// alpha_k = phi^-k with phi the real root of x^5 = x + 1. Every prefix, of any length,
// spreads evenly over coordinates (0, 1) and over (2, 3), the pairs a photon uses
// together (its point on the light, its direction); (0, 2) shows more lattice structure.
// A random shift makes each point uniform. Kept in 64-bit fixed point, so the sum wraps
// exactly instead of rounding.
class Kronecker4 {
 public:
  explicit Kronecker4(Rng& rng) {
    for (uint64_t& s : shift_) s = uint64_t(rng.nextU32()) << 32 | rng.nextU32();
  }
  // The top 24 bits of each coordinate: exact in float and below 1.
  float operator()(uint64_t i, int k) const {
    static constexpr uint64_t kAlpha[4] = {0xdb4f0b9175ae2165ull, 0xbbe0563303a4615full,
                                           0xa0f2ec75a1fe1575ull, 0x89e182857d9ed688ull};
    return static_cast<float>((shift_[k] + i * kAlpha[k]) >> 40) * 0x1p-24f;
  }

 private:
  uint64_t shift_[4];
};

}  // namespace penumbra
