// The studio environment's integrals in closed form, term by term from its definition
// (core/lights/studio_environment.h), for the tests that check the map and the
// renders against them.
#pragma once
#include "core/lights/studio_environment.h"
#include <algorithm>
#include <cmath>
#include <vector>

namespace penumbra::testing {

inline constexpr double kStudioPi = 3.14159265358979323846;

inline double studioKeyCos() { return std::cos(studio::kKeyRadiusDegrees * kStudioPi / 180.0); }

// The integral of the key term over the sphere: 2 pi K integral_c^1 ((t - c) / (1 - c))^2 dt.
inline double studioKeyIntegral() {
  const double c = studioKeyCos();
  return 2.0 * kStudioPi * studio::kKey * (1.0 - c) / 3.0;
}

// The key's first moment along its axis: 2 pi K integral_c^1 f(t) t dt.
inline double studioKeyMoment() {
  const double c = studioKeyCos();
  return 2.0 * kStudioPi * studio::kKey * (1.0 - c) * (c / 3.0 + (1.0 - c) / 4.0);
}

// The integral of L over the sphere of directions.
inline double studioSphereIntegral() {
  using namespace studio;
  return 4.0 * kStudioPi * kGround + 2.0 * kStudioPi * (kHorizon - kGround) + kStudioPi * kZenith +
         studioKeyIntegral();
}

// Whether the key's cap lies wholly on one side of the plane of normal n, where its
// irradiance has the closed form below.
inline bool studioKeyClear(const glm::dvec3& n) {
  const double angle = std::acos(std::clamp(glm::dot(n, studioKeyDirection()), -1.0, 1.0));
  const double r = studio::kKeyRadiusDegrees * kStudioPi / 180.0;
  return angle + r <= 0.5 * kStudioPi || angle - r >= 0.5 * kStudioPi;
}

// E(n), the integral of L(w) max(0, n . w) over the sphere, for a unit n with the key
// clear of its horizon (studioKeyClear):
//   ground, a constant:           pi G
//   the sky's step at the horizon: (H - G) pi (1 + n.y) / 2   (the tilted plane's sky view)
//   the zenith term Z max(0, w.y): Z (2/3) ((pi - g) cos g + sin g), g the angle of n from +y
//                                  (the integral of two clamped cosines)
//   the key, rotationally symmetric about k: (n . k) x its first moment when wholly above
//                                  the plane (the parts across the axis cancel), 0 below.
inline double studioIrradiance(const glm::dvec3& n) {
  using namespace studio;
  const double g = std::acos(std::clamp(n.y, -1.0, 1.0));
  const double nk = glm::dot(n, studioKeyDirection());
  return kStudioPi * kGround + (kHorizon - kGround) * kStudioPi * (1.0 + n.y) / 2.0 +
         kZenith * (2.0 / 3.0) * ((kStudioPi - g) * std::cos(g) + std::sin(g)) +
         (nk > 0.0 ? nk * studioKeyMoment() : 0.0);
}

// Unit normals with the key clear: the axes, the key's own axis and two oblique ones.
inline std::vector<glm::dvec3> studioTestNormals() {
  std::vector<glm::dvec3> n = {{0, 1, 0}, {0, -1, 0}, {1, 0, 0}, {-1, 0, 0}, {0, 0, 1}, {0, 0, -1},
                               studioKeyDirection(), glm::normalize(glm::dvec3(0.6, -0.5, 0.3)),
                               glm::normalize(glm::dvec3(-0.2, 0.9, 0.5))};
  return n;
}

}  // namespace penumbra::testing
