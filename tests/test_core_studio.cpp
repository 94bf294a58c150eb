// The studio environment's map against its closed forms: the map's integral over the
// sphere, and its irradiance E(n) on planes of several normals (each texel's solid
// angle weighted by the clamped cosine, integrated finely), both within 0.1% of the
// continuous definition; texels agree with the radiance they average.
#include "core/lights/studio_environment.h"
#include "support/studio_closed_form.h"
#include <gtest/gtest.h>
#include <cstdio>

namespace penumbra {
namespace {

using testing::kStudioPi;

double rel(double got, double want) { return std::abs(got - want) / std::abs(want); }

// The map's own irradiance: each texel's value times the integral of max(0, n . w) over
// its solid angle, by 8 x 8 equal-area samples (solid angle is uniform in y and phi).
double mapIrradiance(const EnvironmentMap& map, const glm::dvec3& n) {
  constexpr int k = 8;
  // The sub-columns' directions in the xz plane, once.
  std::vector<double> sx(static_cast<size_t>(map.width) * k), sz(sx.size());
  for (size_t c = 0; c < sx.size(); ++c) {
    const double phi = 2.0 * kStudioPi * (c + 0.5) / sx.size() - map.rotation;
    sx[c] = -std::sin(phi);
    sz[c] = std::cos(phi);
  }
  double e = 0.0;
  for (int i = 0; i < map.height; ++i) {
    const double yTop = std::cos(kStudioPi * i / map.height), yBottom = std::cos(kStudioPi * (i + 1) / map.height);
    const double cell = (yTop - yBottom) * 2.0 * kStudioPi / map.width / (k * k);
    for (int a = 0; a < k; ++a) {
      const double y = yTop + (yBottom - yTop) * (a + 0.5) / k, s = std::sqrt(1.0 - y * y);
      for (int j = 0; j < map.width; ++j) {
        double cosines = 0.0;
        for (int b = 0; b < k; ++b) {
          const size_t c = static_cast<size_t>(j) * k + b;
          cosines += std::max(0.0, n.x * s * sx[c] + n.y * y + n.z * s * sz[c]);
        }
        e += map.texels[static_cast<size_t>(i) * map.width + j].r * cosines * cell;
      }
    }
  }
  return e;
}

TEST(StudioEnvironment, MapIntegralIsTheClosedForm) {
  // Sky and ground rows are exact averages; the key's texels 4 x 4 samples of a lobe
  // smooth to first order at its edge. Tolerance 0.1% relative (the key is a fifth).
  const auto map = makeStudioMap(0.0f);
  ASSERT_EQ(map->width, studio::kWidth);
  ASSERT_EQ(map->height, studio::kHeight);
  const double want = testing::studioSphereIntegral();
  std::printf("integral of L: map %.6f, closed form %.6f\n", double(map->integral.r), want);
  EXPECT_LT(rel(map->integral.r, want), 1e-3);
  EXPECT_EQ(map->integral.r, map->integral.g);  // neutral: every channel the same
  EXPECT_EQ(map->integral.r, map->integral.b);
}

TEST(StudioEnvironment, MapIrradianceIsTheClosedFormForEveryTestNormal) {
  // The normals keep the key's cap clear of their horizon (the closed form's domain);
  // the map's E(n) within 0.1% of the continuous definition's.
  const auto map = makeStudioMap(0.0f);
  for (const glm::dvec3& n : testing::studioTestNormals()) {
    ASSERT_TRUE(testing::studioKeyClear(n));
    const double got = mapIrradiance(*map, n), want = testing::studioIrradiance(n);
    std::printf("E(%.3f, %.3f, %.3f): map %.5f, closed form %.5f\n", n.x, n.y, n.z, got, want);
    EXPECT_LT(rel(got, want), 1e-3) << n.x << " " << n.y << " " << n.z;
  }
}

TEST(StudioEnvironment, TexelsHoldTheRadianceTheyAverage) {
  // Away from the key and the horizon a texel is the radiance at its centre to the
  // curvature of max(0, y) over one row (< 1e-4); the key's centre texel is near its
  // peak, the ground below the sky, the zenith the sky's brightest.
  const auto map = makeStudioMap(0.0f);
  const int w = map->width, h = map->height;
  auto texel = [&](int i, int j) { return double(map->texels[static_cast<size_t>(i) * w + j].r); };
  auto centre = [&](int i, int j) {
    const double t = kStudioPi * (i + 0.5) / h, p = 2.0 * kStudioPi * (j + 0.5) / w;
    return glm::dvec3(-std::sin(t) * std::sin(p), std::cos(t), std::sin(t) * std::cos(p));
  };
  for (int i : {3, 40, 100, 127, 128, 200, 250}) {
    for (int j : {0, 128, 300, 511}) {
      const glm::dvec3 d = centre(i, j);
      if (glm::dot(d, studioKeyDirection()) > std::cos(25.0 * kStudioPi / 180.0)) continue;
      EXPECT_NEAR(texel(i, j), studioRadiance(d), 1e-4) << i << ", " << j;
    }
  }
  EXPECT_NEAR(texel(h - 1, 0), studio::kGround, 1e-6);
  EXPECT_NEAR(texel(0, 0), studio::kHorizon + studio::kZenith, 1e-4);
  // The key's centre: 45 degrees up (row 64), azimuth -30 degrees, i.e. phi = 30 degrees.
  const int ki = h / 4, kj = w * 30 / 360;
  EXPECT_GT(texel(ki, kj), studio::kHorizon + 0.9 * studio::kKey);
}

TEST(StudioEnvironment, RotationTurnsTheKeyAboutUp) {
  // The map turned 90 degrees: E on a plane is E(n) of the unturned studio with n
  // turned back, -90 degrees about +y ((x, z) -> (-z, x) undoes a turn of +z towards +x).
  const auto map = makeStudioMap(90.0f);
  const glm::dvec3 n(0.0, 0.0, 1.0), back(-1.0, 0.0, 0.0);
  ASSERT_TRUE(testing::studioKeyClear(back));
  EXPECT_LT(rel(mapIrradiance(*map, n), testing::studioIrradiance(back)), 1e-3);
}

}  // namespace
}  // namespace penumbra
