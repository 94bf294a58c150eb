// The environment light's map sampling against its pdf: a chi-squared test of
// sampleEnvironmentSphere against environmentPdf (cells on the map's own pixel grid, so
// the piecewise-constant pdf integrates exactly by the midpoint rule), the pdf's
// integral over the sphere, the photon weights' mean, and importance sampling against
// uniform sampling at equal samples (RMSE of the irradiance under one bright patch).
#include "core/lights/environment_map.h"
#include "core/rng.h"
#include "core/sampling.h"
#include "support/chi2.h"
#include <gtest/gtest.h>
#include <cmath>
#include <cstdio>
#include <vector>

namespace penumbra {
namespace {

constexpr double kPiD = 3.14159265358979323846;

// A 32 x 16 sky: a smooth gradient (brighter towards +y and to one side) with a
// bright 2 x 2 patch, coloured so the channels differ.
std::vector<Color> skyTexels(int w, int h, float patch) {
  std::vector<Color> t(static_cast<size_t>(w) * h);
  for (int i = 0; i < h; ++i) {
    for (int j = 0; j < w; ++j) {
      const float g = 0.05f + 0.5f * float(h - i) / float(h) + 0.2f * float(j) / float(w);
      t[static_cast<size_t>(i) * w + j] = Color(g, 0.8f * g, 0.6f * g);
    }
  }
  for (int i = 4; i < 6; ++i) {
    for (int j = 20; j < 22; ++j) t[static_cast<size_t>(i) * w + j] = Color(patch, 0.9f * patch, 0.7f * patch);
  }
  return t;
}

Vec3 mapDirection(const EnvironmentMap& map, double theta, double phiMap) {
  const double phi = phiMap - map.rotation;
  return Vec3(glm::dvec3(-std::sin(theta) * std::sin(phi), std::cos(theta), std::sin(theta) * std::cos(phi)));
}

TEST(EnvironmentMap, SamplerMatchesItsPdfChiSquared) {
  // One cell per map pixel (rotation 30 degrees: cells follow the turned map). Expected
  // counts: N x the integral of environmentPdf over the cell, midpoint rule on 4 x 4
  // points inside it: pdf x sin(theta) is constant over a pixel, so the rule is exact
  // up to float rounding. Pass: p-value above 1e-3 (one fixed seed: deterministic).
  const int w = 32, h = 16, n = 400000;
  const auto map = makeEnvironmentMap(w, h, skyTexels(w, h, 40.0f), 30.0f);
  const Light light = makeEnvironmentLight(Color(1.0f), 1.0f, map);
  std::vector<double> observed(static_cast<size_t>(w) * h, 0.0), expected(observed.size(), 0.0);
  Rng rng(99);
  int invalid = 0;
  for (int k = 0; k < n; ++k) {
    const EnvironmentSample e = sampleEnvironmentSphere(light, rng.uniform(), rng.uniform());
    if (!e.valid) { ++invalid; continue; }
    const double theta = std::acos(std::clamp(double(e.wi.y), -1.0, 1.0));
    double phi = std::atan2(-double(e.wi.x), double(e.wi.z)) + map->rotation;
    phi -= 2.0 * kPiD * std::floor(phi / (2.0 * kPiD));
    const int i = std::clamp(int(theta / kPiD * h), 0, h - 1), j = std::clamp(int(phi / (2.0 * kPiD) * w), 0, w - 1);
    observed[static_cast<size_t>(i) * w + j] += 1.0;
  }
  EXPECT_EQ(invalid, 0);
  const int sub = 4;
  const double dT = kPiD / (h * sub), dP = 2.0 * kPiD / (w * sub);
  double mass = 0.0;
  for (int a = 0; a < h * sub; ++a) {
    const double theta = (a + 0.5) * dT;
    for (int b = 0; b < w * sub; ++b) {
      const double m = environmentPdf(light, Vec3(0, 1, 0), mapDirection(*map, theta, (b + 0.5) * dP)) *
                       std::sin(theta) * dT * dP;
      expected[static_cast<size_t>(a / sub) * w + b / sub] += m * n;
      mass += m;
    }
  }
  EXPECT_NEAR(mass, 1.0, 1e-4) << "the pdf's integral over the pixel-aligned cells";
  const chi2::Result r = chi2::test(observed, expected, n);
  EXPECT_TRUE(r.failure.empty()) << r.failure;
  EXPECT_GT(r.pValue, 1e-3) << "chi2 " << r.statistic << " dof " << r.dof << r.worst;
}

TEST(EnvironmentMap, PdfIntegratesToOneOverTheSphere) {
  // Midpoint rule on a 960 x 1696 (theta, phi) grid over the 32 x 16 map turned by 77
  // degrees: 60 rows per map row and 53 columns per map column, so however the turn cuts
  // a pixel's edges, the cells whose midpoints fall inside it add up to its exact
  // extent; tolerance 1e-4 (float pdfs summed in double). A constant sky's cosine pdf
  // (about a tilted normal) integrates to 1 within 1e-3 (its smooth edge at the horizon).
  const auto map = makeEnvironmentMap(32, 16, skyTexels(32, 16, 40.0f), 77.0f);
  const Light mapped = makeEnvironmentLight(Color(1.0f), 3.0f, map);
  const Light sky = makeEnvironmentLight(Color(0.5f), 2.0f, nullptr);
  const Vec3 n = glm::normalize(Vec3(0.3f, 0.4f, -0.8f));
  const int nt = 960, np = 1696;
  double sumMap = 0.0, sumSky = 0.0;
  for (int a = 0; a < nt; ++a) {
    const double theta = (a + 0.5) * kPiD / nt, dw = std::sin(theta) * (kPiD / nt) * (2.0 * kPiD / np);
    for (int b = 0; b < np; ++b) {
      const double phi = (b + 0.5) * 2.0 * kPiD / np;
      const Vec3 d(glm::dvec3(std::sin(theta) * std::cos(phi), std::cos(theta), std::sin(theta) * std::sin(phi)));
      sumMap += environmentPdf(mapped, n, d) * dw;
      sumSky += environmentPdf(sky, n, d) * dw;
    }
  }
  EXPECT_NEAR(sumMap, 1.0, 1e-4);
  EXPECT_NEAR(sumSky, 1.0, 1e-3);
}

TEST(EnvironmentMap, SampledPdfIsThePdfOfTheSampledDirection) {
  // What a sample reports is what environmentPdf says of its direction (the MIS weights
  // need both): within 1e-3 relative, but for samples on a pixel edge, where float
  // rounding may put the direction in the neighbour (at most 0.1% of them).
  const auto map = makeEnvironmentMap(32, 16, skyTexels(32, 16, 40.0f), -45.0f);
  const Light light = makeEnvironmentLight(Color(1.0f), 1.0f, map);
  Rng rng(7);
  int off = 0;
  const int n = 100000;
  for (int k = 0; k < n; ++k) {
    const EnvironmentSample e = sampleEnvironmentSphere(light, rng.uniform(), rng.uniform());
    ASSERT_TRUE(e.valid);
    const float p = environmentPdf(light, Vec3(0, 1, 0), e.wi);
    off += std::abs(p - e.pdf) > 1e-3f * e.pdf;
  }
  EXPECT_LE(off, n / 1000);
}

TEST(EnvironmentMap, PhotonWeightsAverageOneAndPowerIsPiR2TimesTheIntegral) {
  // Each photon carries power / count x weight; the weights' mean per channel must be
  // 1 (within 1%, 200k photons) so the emitted flux is the light's power, and that
  // power is pi R^2 x the integral of L (a constant sky: pi R^2 4 pi L, to 1e-5).
  const auto map = makeEnvironmentMap(32, 16, skyTexels(32, 16, 40.0f), 10.0f);
  const Light light = makeEnvironmentLight(Color(1.0f, 0.5f, 0.25f), 2.0f, map);
  const SceneSphere bounds{Vec3(1.0f, 2.0f, 3.0f), 4.0f};
  Rng rng(11);
  glm::dvec3 sum(0.0);
  const int n = 200000;
  for (int k = 0; k < n; ++k) {
    const PhotonRay r = environmentPhoton(light, bounds, rng.uniform(), rng.uniform(), rng.uniform(), rng.uniform());
    sum += glm::dvec3(r.weight);
    // Every photon starts outside the bounding sphere, on a line through its disc.
    const Vec3 c = bounds.center - r.origin;
    const float along = glm::dot(c, r.dir);
    ASSERT_GT(glm::length(c), bounds.radius);
    ASSERT_GT(along, 0.0f);
    ASSERT_LE(glm::dot(c, c) - along * along, bounds.radius * bounds.radius * 1.0001f);
  }
  for (int c = 0; c < 3; ++c) EXPECT_NEAR(sum[c] / n, 1.0, 0.01) << c;
  const Light sky = makeEnvironmentLight(Color(0.5f), 2.0f, nullptr);
  const Color power = lightPower(sky, bounds);
  EXPECT_NEAR(power.r, kPiD * 16.0 * 4.0 * kPiD * 1.0, 1e-5 * power.r);
}

TEST(EnvironmentMap, ImportanceSamplingBeatsUniformOnABrightPatch) {
  // Irradiance on a surface facing +y under a 64 x 32 map: a dim sky (0.05) and one
  // 2 x 2 patch 5000 times brighter. Reference: the piecewise-constant map integrated
  // exactly (each pixel's integral of cos theta over its solid angle). RMSE over 400
  // independent estimates of 64 samples each, by luminance importance sampling and by
  // uniform sphere sampling (pdf 1 / 4 pi). Asserted: IS below a quarter of uniform.
  const int w = 64, h = 32;
  std::vector<Color> texels(static_cast<size_t>(w) * h, Color(0.05f));
  for (int i = 6; i < 8; ++i)
    for (int j = 40; j < 42; ++j) texels[static_cast<size_t>(i) * w + j] = Color(250.0f);
  const auto map = makeEnvironmentMap(w, h, texels, 0.0f);
  const Light light = makeEnvironmentLight(Color(1.0f), 1.0f, map);
  double reference = 0.0;
  for (int i = 0; i < h / 2; ++i) {  // the upper hemisphere: rows above theta = pi / 2
    const double t0 = kPiD * i / h, t1 = kPiD * (i + 1) / h;
    const double band = 0.5 * (std::sin(t1) * std::sin(t1) - std::sin(t0) * std::sin(t0)) * 2.0 * kPiD / w;
    for (int j = 0; j < w; ++j) reference += texels[static_cast<size_t>(i) * w + j].r * band;
  }
  const int trials = 400, samples = 64;
  double seIs = 0.0, seUniform = 0.0;
  for (int t = 0; t < trials; ++t) {
    Rng rng(hashKey(2024, t));
    double is = 0.0, uni = 0.0;
    for (int k = 0; k < samples; ++k) {
      const EnvironmentSample e = sampleEnvironmentSphere(light, rng.uniform(), rng.uniform());
      if (e.valid && e.wi.y > 0.0f) is += e.radiance.r * e.wi.y / e.pdf;
      const Vec3 d = uniformSphere(rng.uniform(), rng.uniform());
      if (d.y > 0.0f) uni += environmentRadiance(light, d).r * d.y * 4.0 * kPiD;
    }
    seIs += std::pow(is / samples - reference, 2.0);
    seUniform += std::pow(uni / samples - reference, 2.0);
  }
  const double rmseIs = std::sqrt(seIs / trials), rmseUniform = std::sqrt(seUniform / trials);
  std::printf("irradiance %.4f: RMSE at %d samples: importance %.4f (%.2f%%), uniform %.4f (%.2f%%)\n", reference,
              samples, rmseIs, 100.0 * rmseIs / reference, rmseUniform, 100.0 * rmseUniform / reference);
  EXPECT_LT(rmseIs, 0.25 * rmseUniform);
}

}  // namespace
}  // namespace penumbra
