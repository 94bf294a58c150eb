// The studio environment's radiance and its lat-long map, texel by texel.
#include "core/lights/studio_environment.h"
#include <algorithm>
#include <cmath>

namespace penumbra {

namespace {

constexpr double kDegrees = M_PI / 180.0;
constexpr int kKeySamples = 4;  // per texel side, where a texel may touch the key

double keyLobe(double t) {
  const double c = std::cos(studio::kKeyRadiusDegrees * kDegrees);
  if (t <= c) return 0.0;
  const double u = (t - c) / (1.0 - c);
  return studio::kKey * u * u;
}

// The lat-long direction of height y and angle phi (environment_map.h's convention).
glm::dvec3 direction(double y, double phi) {
  const double s = std::sqrt(std::max(0.0, 1.0 - y * y));
  return {-s * std::sin(phi), y, s * std::cos(phi)};
}

}  // namespace

glm::dvec3 studioKeyDirection() {
  const double a = studio::kKeyAzimuthDegrees * kDegrees, e = studio::kKeyElevationDegrees * kDegrees;
  return {std::sin(a) * std::cos(e), std::sin(e), std::cos(a) * std::cos(e)};
}

double studioRadiance(const glm::dvec3& w) {
  const double sky = w.y > 0.0 ? studio::kHorizon + studio::kZenith * w.y : studio::kGround;
  return sky + keyLobe(glm::dot(w, studioKeyDirection()));
}

std::shared_ptr<const EnvironmentMap> makeStudioMap(float rotationDegrees) {
  const int w = studio::kWidth, h = studio::kHeight;
  const glm::dvec3 key = studioKeyDirection();
  // A texel whose centre lies further from the key than its radius plus two texel
  // diagonals cannot touch it.
  const double reach = std::cos((studio::kKeyRadiusDegrees + 2.0 * 360.0 / w) * kDegrees);
  std::vector<Color> texels(static_cast<size_t>(w) * h);
  for (int i = 0; i < h; ++i) {
    const double yTop = std::cos(M_PI * i / h), yBottom = std::cos(M_PI * (i + 1) / h);
    // Solid angle is uniform in y, so the row's mean of max(0, y) is its middle y; the
    // horizon falls between rows (h is even).
    const double yMid = 0.5 * (yTop + yBottom);
    const double sky = yMid > 0.0 ? studio::kHorizon + studio::kZenith * yMid : studio::kGround;
    for (int j = 0; j < w; ++j) {
      const double phi = 2.0 * M_PI * (j + 0.5) / w;
      double lobe = 0.0;
      if (glm::dot(direction(yMid, phi), key) > reach) {
        for (int a = 0; a < kKeySamples; ++a) {
          const double y = yTop + (yBottom - yTop) * (a + 0.5) / kKeySamples;
          for (int b = 0; b < kKeySamples; ++b) {
            lobe += keyLobe(glm::dot(direction(y, 2.0 * M_PI * (j + (b + 0.5) / kKeySamples) / w), key));
          }
        }
        lobe /= kKeySamples * kKeySamples;
      }
      texels[static_cast<size_t>(i) * w + j] = Color(static_cast<float>(sky + lobe));
    }
  }
  return makeEnvironmentMap(w, h, std::move(texels), rotationDegrees);
}

void addStudioEnvironment(Scene& scene, const Color& color, float intensity, float rotationDegrees) {
  scene.lights.push_back(makeEnvironmentLight(color, intensity, makeStudioMap(rotationDegrees)));
  scene.render.environmentBackground = Color(studio::kBackground);
}

}  // namespace penumbra
