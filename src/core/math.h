// Vector types and the few geometric helpers every stage shares.
// penumbra works in single precision (Embree's), with GLM for the vector algebra.
#pragma once
#include <glm/glm.hpp>
#include <glm/gtc/constants.hpp>
#include <algorithm>
#include <cmath>
#include <cstdint>
#include <limits>

namespace penumbra {

using Vec2 = glm::vec2;
using Vec3 = glm::vec3;
using Color = glm::vec3;  // linear RGB

constexpr float kPi = glm::pi<float>();
constexpr float kInf = std::numeric_limits<float>::infinity();

inline float maxComponent(const Vec3& v) { return std::max(v.x, std::max(v.y, v.z)); }
inline float luminance(const Color& c) { return 0.2126f * c.r + 0.7152f * c.g + 0.0722f * c.b; }
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

// Self-intersection offset. A float position of magnitude m carries an absolute
// error of about m * 2^-23 per operation; after the handful of operations of a ray
// hit that is a few hundred ulps. So the offset grows with the hit point's largest
// coordinate instead of being a fixed epsilon that fails far from the origin and
// over-shoots near it: eps = kOffsetRelative * (1 + max|p_i|).
constexpr float kOffsetRelative = 1.0f / (1 << 15);  // ~3.05e-5, ~256 ulps
inline float offsetEpsilon(const Vec3& p) {
  return kOffsetRelative * (1.0f + maxComponent(glm::abs(p)));
}
// Moves p off the surface with geometric normal ng, towards the side dir points to.
inline Vec3 offsetRayOrigin(const Vec3& p, const Vec3& ng, const Vec3& dir) {
  float eps = offsetEpsilon(p);
  return glm::dot(ng, dir) >= 0.0f ? p + eps * ng : p - eps * ng;
}

}  // namespace penumbra
