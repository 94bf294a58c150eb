// Vector types and the few geometric helpers every stage shares.
// penumbra works in single precision (Embree's), with GLM for the vector algebra.
#pragma once
#include <glm/glm.hpp>
#include <glm/gtc/constants.hpp>
#include <algorithm>
#include <cmath>
#include <cstdint>
#include <cstring>
#include <limits>

namespace penumbra {

using Vec2 = glm::vec2;
using Vec3 = glm::vec3;
using Color = glm::vec3;  // linear RGB

constexpr float kPi = glm::pi<float>();
constexpr float kInf = std::numeric_limits<float>::infinity();

inline float maxComponent(const Vec3& v) { return std::max(v.x, std::max(v.y, v.z)); }
inline float luminance(const Color& c) { return 0.2126f * c.r + 0.7152f * c.g + 0.0722f * c.b; }
// normalize(a x b): in float, or in double where the float cross product's squared
// length overflows (vectors longer than ~1e9, as a huge quad's edges).
inline Vec3 unitCross(const Vec3& a, const Vec3& b) {
  const Vec3 c = glm::cross(a, b);
  if (std::isfinite(glm::dot(c, c))) return glm::normalize(c);
  return Vec3(glm::normalize(glm::cross(glm::dvec3(a), glm::dvec3(b))));
}
inline bool isFinite(const Vec3& v) {
  return std::isfinite(v.x) && std::isfinite(v.y) && std::isfinite(v.z);
}

// Right-handed orthonormal basis around a unit vector n (Duff et al. 2017): no
// branch on an arbitrary axis, no singularity except the exact -z pole it handles.
inline void orthonormalBasis(const Vec3& n, Vec3& t, Vec3& b) {
  float sign = std::copysign(1.0f, n.z);
  float a = -1.0f / (sign + n.z);
  float c = n.x * n.y * a;
  t = Vec3(1.0f + sign * n.x * n.x * a, sign * c, -sign * n.x);
  b = Vec3(c, sign + n.y * n.y * a, -n.y);
}

// Self-intersection offsets from floating-point error bounds (Higham's gamma_n,
// as in pbrt-v4's robust spawned rays): a computed hit point lies within `error`
// of the true surface along its normal, and that error follows the magnitudes the
// point was computed from. No absolute floor: a 1e-6 scene is as safe as a 1e6 one.
constexpr float kUnitRoundoff = std::numeric_limits<float>::epsilon() * 0.5f;
constexpr float gammaBound(int n) { return n * kUnitRoundoff / (1.0f - n * kUnitRoundoff); }

// A float's bits and back (C++17's std::bit_cast).
inline uint32_t floatBits(float v) {
  uint32_t b;
  std::memcpy(&b, &v, sizeof b);
  return b;
}
inline float bitsToFloat(uint32_t b) {
  float v;
  std::memcpy(&v, &b, sizeof v);
  return v;
}

// The next float above v (nextFloatUp) or below it (nextFloatDown), as std::nextafter
// towards +inf or -inf answers, without its library call on every spawned ray.
inline float nextFloatUp(float v) {
  if (v == kInf || v != v) return v;
  if (v == 0.0f) v = 0.0f;  // -0 steps up to the smallest positive float
  const uint32_t bits = floatBits(v);
  return bitsToFloat(v > 0.0f || bits == 0u ? bits + 1u : bits - 1u);
}
inline float nextFloatDown(float v) { return -nextFloatUp(-v); }

// Moves p by `error` along the geometric normal ng, to the side dir points to, then
// rounds every moved coordinate one more ulp away, so the rounding of the addition
// cannot pull the origin back into the error box.
inline Vec3 offsetRayOrigin(const Vec3& p, const Vec3& ng, float error, const Vec3& dir) {
  const Vec3 n = glm::dot(ng, dir) < 0.0f ? -ng : ng;
  Vec3 o = p + error * n;
  for (int i = 0; i < 3; ++i) {
    if (n[i] > 0.0f) o[i] = nextFloatUp(o[i]);
    else if (n[i] < 0.0f) o[i] = nextFloatDown(o[i]);
  }
  return o;
}

// Where a shadow ray towards an exactly known point (a point light) stops: a few
// dozen ulps short, the rounding of the distance, and nothing more, so an occluder
// 1e-5 of the distance from the light still blocks it.
constexpr float kShadowRayShortening = 1.0f / (1 << 20);

}  // namespace penumbra
