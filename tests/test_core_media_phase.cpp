// The Henyey–Greenstein phase function: normalised over the sphere (adaptive Simpson in
// cosTheta), its sampler's directions distributed as it says (chi-squared on a
// (cosTheta, phi) grid about the incoming direction, mean cosine = g), each sample's
// pdf equal to the function, and finite unit directions at g = +-0.999999.
#include "core/media/phase_function.h"
#include "core/rng.h"
#include "support/adaptive_simpson.h"
#include "support/chi2.h"
#include <gtest/gtest.h>
#include <string>
#include <vector>

namespace penumbra {
namespace {

const double kTwoPi = 2.0 * glm::pi<double>();
constexpr int kCosBins = 40, kPhiBins = 8;
constexpr int kSamples = 400000;
const std::vector<float> kChi2G = {-0.7f, 0.0f, 0.5f, 0.9f};
// A family-wise 1% false alarm rate over the chi-squared cases in this file.
const double kLevel = chi2::sidakLevel(0.01, int(kChi2G.size()));

// In double: the float wrapper rounds cosTheta, coarser than a g = -0.999 lobe.
double phaseOfCos(float g, double mu) { return henyeyGreensteinD(g, mu); }

TEST(HenyeyGreenstein, IntegratesToOneOverTheSphere) {
  for (float g : {-0.999f, -0.7f, -0.2f, 0.0f, 0.3f, 0.9f, 0.99f}) {
    const double total =
        kTwoPi * testing::adaptiveSimpson([&](double mu) { return phaseOfCos(g, mu); }, -1.0, 1.0, 1e-9, 256);
    EXPECT_NEAR(total, 1.0, 1e-6) << "g = " << g;
  }
}

TEST(HenyeyGreenstein, SamplesFollowTheFunctionAndTheirPdfIsIt) {
  // An incoming direction off every axis, so the sampler's basis is exercised.
  const Vec3 before = glm::normalize(Vec3(0.3f, -0.5f, 0.8f));
  Vec3 t, b;
  orthonormalBasis(before, t, b);
  uint64_t seed = 11;
  for (float g : kChi2G) {
    const std::string name = "g = " + std::to_string(g);
    Rng rng(seed++);
    std::vector<double> observed(kCosBins * kPhiBins, 0.0);
    double sumCos = 0.0, worstPdf = 0.0;
    for (int n = 0; n < kSamples; ++n) {
      const float u1 = rng.uniform(), u2 = rng.uniform();
      const PhaseSample s = sampleHenyeyGreenstein(g, before, u1, u2);
      const double mu = std::clamp(double(glm::dot(s.dir, before)), -1.0, 1.0);
      double phi = std::atan2(double(glm::dot(s.dir, b)), double(glm::dot(s.dir, t)));
      if (phi < 0.0) phi += kTwoPi;
      const int i = std::clamp(int((mu + 1.0) * 0.5 * kCosBins), 0, kCosBins - 1);
      const int j = std::clamp(int(phi / kTwoPi * kPhiBins), 0, kPhiBins - 1);
      observed[i * kPhiBins + j] += 1.0;
      sumCos += mu;
      const double eval = henyeyGreenstein(g, float(mu));
      worstPdf = std::max(worstPdf, std::abs(s.pdf - eval) / eval);
    }
    // Each cell's mass: the function integrated over its cosTheta range (adaptive
    // Simpson), times its share of phi; symmetric about the axis.
    std::vector<double> expected(observed.size());
    for (int i = 0; i < kCosBins; ++i) {
      const double lo = -1.0 + 2.0 * i / kCosBins, hi = -1.0 + 2.0 * (i + 1) / kCosBins;
      const double mass =
          kTwoPi * testing::adaptiveSimpson([&](double mu) { return phaseOfCos(g, mu); }, lo, hi, 1e-11, 8);
      for (int j = 0; j < kPhiBins; ++j) expected[i * kPhiBins + j] = kSamples * mass / kPhiBins;
    }
    const chi2::Result r = chi2::test(observed, expected, kSamples);
    EXPECT_TRUE(r.failure.empty()) << name << ": " << r.failure;
    EXPECT_GE(r.pValue, kLevel) << name << ": chi2 " << r.statistic << " on " << r.dof << " dof;" << r.worst;
    // The mean cosine of Henyey–Greenstein is g; its variance is below 1.
    EXPECT_NEAR(sumCos / kSamples, g, 5.0 / std::sqrt(double(kSamples))) << name;
    EXPECT_LT(worstPdf, 1e-3) << name << ": a sample's pdf differs from the function";
  }
}

TEST(HenyeyGreenstein, NearlyDeltaLobesGiveFiniteUnitDirections) {
  const Vec3 before = glm::normalize(Vec3(-0.2f, 0.9f, 0.1f));
  for (float g : {0.999999f, -0.999999f}) {
    Rng rng(5);
    double sumCos = 0.0;
    const int n = 20000;
    for (int k = 0; k < n; ++k) {
      const PhaseSample s = sampleHenyeyGreenstein(g, before, rng.uniform(), rng.uniform());
      ASSERT_TRUE(isFinite(s.dir)) << g;
      ASSERT_NEAR(glm::length(s.dir), 1.0f, 1e-5f) << g;
      ASSERT_TRUE(std::isfinite(s.pdf) && s.pdf > 0.0f) << g << ": pdf " << s.pdf;
      sumCos += glm::dot(s.dir, before);
    }
    // Almost every sample continues straight on (g > 0) or turns straight back.
    EXPECT_NEAR(sumCos / n, g, 1e-3) << g;
    EXPECT_TRUE(std::isfinite(henyeyGreenstein(g, 1.0f)) && std::isfinite(henyeyGreenstein(g, -1.0f))) << g;
  }
}

}  // namespace
}  // namespace penumbra
