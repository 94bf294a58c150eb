// A homogeneous medium's closed forms and sampled flights against their analytic
// answers: slab transmittance exp(-sigmaT d), collision distances (chi-squared), each
// RGB channel's expected weights, truncated free flights, and the extremes (sigma 0,
// sigma 1e30, an infinite medium, an empty segment, exp underflow).
#include "core/media/homogeneous.h"
#include "support/media_tracking.h"
#include <gtest/gtest.h>
#include <string>

namespace penumbra {
namespace {

using testing::collisionChi2;
using testing::collisions;
using testing::makeMedium;

const Vec3 kOrigin(0.5f, -1.0f, 2.0f);
const Vec3 kDir = glm::normalize(Vec3(1.0f, 2.0f, -0.5f));
constexpr int kCases = 3;  // chi-squared cases in this file, for the family-wise level
const double kLevel = chi2::sidakLevel(0.01, kCases);

void expectChi2(const chi2::Result& r, const std::string& name) {
  EXPECT_TRUE(r.failure.empty()) << name << ": " << r.failure;
  EXPECT_GE(r.pValue, kLevel) << name << ": chi2 " << r.statistic << " on " << r.dof << " dof;" << r.worst;
}

TEST(HomogeneousMedium, SlabTransmittanceIsBeerLambert) {
  for (float sigma : {0.01f, 0.3f, 1.0f, 4.7f}) {
    for (float d : {0.05f, 1.0f, 2.5f}) {
      const float a = 2.0f, b = a + d;
      const Medium m = makeMedium(Color(0.2f * sigma, 0.5f * sigma, sigma), Color(0.3f * sigma, 0.1f, 0.0f));
      const Color st = m.sigmaT();
      Rng rng(1);
      const Color closed = transmittance(st, d), tracked = mediumTransmittance(m, kOrigin, kDir, a, b, rng);
      for (int c = 0; c < 3; ++c) {
        const double exact = std::exp(-double(st[c]) * (double(b) - double(a)));
        EXPECT_NEAR(closed[c], std::exp(-double(st[c]) * d), 1e-5) << sigma << " " << d << " channel " << c;
        EXPECT_NEAR(tracked[c], exact, 1e-5) << sigma << " " << d << " channel " << c;
      }
    }
  }
}

TEST(HomogeneousMedium, GreyCollisionsAreExponentialWithAlbedoWeights) {
  // sigmaT 2 over [1, 2.5]: collisions with density 2 e^{-2x}, P(none) = e^{-3}.
  const Medium m = makeMedium(Color(0.5f), Color(1.5f));
  const float a = 1.0f, b = 2.5f, d = b - a;
  const auto s = collisions(m, kOrigin, kDir, a, b, 200000, 7, 30, d);
  ASSERT_TRUE(s.finite);
  expectChi2(collisionChi2(s, [](double x) { return 1.0 - std::exp(-2.0 * x); }, d, std::exp(-2.0 * d)), "grey");
  // A grey medium's weights are exact: the albedo on a collision, 1 without.
  Rng rng(3);
  for (int k = 0; k < 1000; ++k) {
    const MediumCollision c = sampleCollision(m, kOrigin, kDir, a, b, rng);
    for (int ch = 0; ch < 3; ++ch) EXPECT_FLOAT_EQ(c.weight[ch], c.collided ? 0.75f : 1.0f);
  }
}

TEST(HomogeneousMedium, RgbWeightsAreUnbiasedPerChannel) {
  // Channels of very different sigmaT: the collision density is the channels' mixture,
  // and each channel's mean weight is its own transmittance / scattered fraction.
  const Color sa(0.1f, 0.8f, 0.5f), ss(0.4f, 0.2f, 2.5f);
  const Medium m = makeMedium(sa, ss);
  const Color st = m.sigmaT();  // 0.5, 1, 3
  const float a = 0.5f, b = 2.0f, d = b - a;
  const int n = 300000;
  const auto s = collisions(m, kOrigin, kDir, a, b, n, 19, 30, d);
  ASSERT_TRUE(s.finite);
  const auto mixture = [&](double x) { return testing::heroMixtureCdf(st, x); };
  expectChi2(collisionChi2(s, mixture, d, 1.0 - mixture(d)), "rgb mixture");
  for (int c = 0; c < 3; ++c) {
    const double tr = std::exp(-double(st[c]) * d), scattered = double(ss[c]) / st[c] * (1.0 - tr);
    EXPECT_NEAR(s.weightNone[c].mean(), tr, 5.0 * s.weightNone[c].stdError() + 1e-6) << "channel " << c;
    EXPECT_NEAR(s.weightHit[c].mean(), scattered, 5.0 * s.weightHit[c].stdError() + 1e-6) << "channel " << c;
  }
  // The balance heuristic over channels bounds every weight by 3 x the largest albedo.
  EXPECT_LE(s.maxWeight, 3.0 * 0.84 + 1e-5);
}

TEST(HomogeneousMedium, InfiniteMediumWithAClearChannel) {
  // b = inf: a channel with sigmaT 0 sees T = 1 and never scatters; the others always
  // collide, each scattering its albedo on average.
  const Medium m = makeMedium(Color(0.0f, 0.5f, 0.25f), Color(0.0f, 0.5f, 1.0f));
  const float a = 0.0f, b = kInf;
  const auto s = collisions(m, kOrigin, kDir, a, b, 200000, 23, 20, 10.0f);
  ASSERT_TRUE(s.finite);
  const double albedo[3] = {0.0, 0.5, 0.8};
  EXPECT_NEAR(s.weightNone[0].mean(), 1.0, 5.0 * s.weightNone[0].stdError() + 1e-6);
  for (int c = 1; c < 3; ++c) EXPECT_EQ(s.weightNone[c].mean(), 0.0) << c;
  for (int c = 0; c < 3; ++c) {
    EXPECT_NEAR(s.weightHit[c].mean(), albedo[c], 5.0 * s.weightHit[c].stdError() + 1e-6) << c;
  }
  Rng rng(2);
  const Color t = mediumTransmittance(m, kOrigin, kDir, a, b, rng);
  EXPECT_EQ(t, Color(1.0f, 0.0f, 0.0f));
  const Color tAll = transmittance(Color(0.0f), kInf);
  EXPECT_EQ(tAll, Color(1.0f));
}

TEST(HomogeneousMedium, ExtremeCoefficientsStayFinite) {
  Rng rng(4);
  // sigma 0: never collides, T = 1, weight exactly 1, over finite and infinite segments.
  const Medium vacuum = makeMedium(Color(0.0f), Color(0.0f));
  for (float b : {3.0f, kInf}) {
    EXPECT_EQ(mediumTransmittance(vacuum, kOrigin, kDir, 0.0f, b, rng), Color(1.0f));
    for (int k = 0; k < 100; ++k) {
      const MediumCollision c = sampleCollision(vacuum, kOrigin, kDir, 0.0f, b, rng);
      EXPECT_FALSE(c.collided);
      EXPECT_EQ(c.weight, Color(1.0f));
    }
  }
  EXPECT_EQ(sampleFreeFlight(0.0f, 0.0f), kInf);
  // sigma 1e30: T = 0, collisions at once with the albedo as weight; no NaN or inf.
  const Medium wall = makeMedium(Color(0.5e30f), Color(0.5e30f));
  EXPECT_EQ(mediumTransmittance(wall, kOrigin, kDir, 1.0f, 2.0f, rng), Color(0.0f));
  for (int k = 0; k < 100; ++k) {
    const MediumCollision c = sampleCollision(wall, kOrigin, kDir, 1.0f, kInf, rng);
    EXPECT_TRUE(c.collided);
    EXPECT_GE(c.t, 1.0f);
    EXPECT_LT(c.t, 1.0f + 1e-6f);
    EXPECT_FLOAT_EQ(c.weight.g, 0.5f);
  }
  // Mixed extremes and exp underflow (sigma d = 1e4): weights finite and >= 0.
  const Medium mixed = makeMedium(Color(1e30f, 100.0f, 0.0f), Color(0.0f, 1.0f, 0.0f));
  const auto s = collisions(mixed, kOrigin, kDir, 0.0f, 100.0f, 20000, 29, 10, 100.0f);
  EXPECT_TRUE(s.finite);
  EXPECT_NEAR(s.weightNone[2].mean(), 1.0, 5.0 * s.weightNone[2].stdError() + 1e-6);
  EXPECT_EQ(s.weightNone[0].mean(), 0.0);
  EXPECT_NEAR(s.weightHit[1].mean(), 0.01, 5.0 * s.weightHit[1].stdError() + 1e-6);
  // An empty segment (a = b): nothing happens.
  EXPECT_EQ(mediumTransmittance(wall, kOrigin, kDir, 2.0f, 2.0f, rng), Color(1.0f));
  const MediumCollision none = sampleCollision(wall, kOrigin, kDir, 2.0f, 2.0f, rng);
  EXPECT_FALSE(none.collided);
  EXPECT_EQ(none.weight, Color(1.0f));
}

TEST(HomogeneousMedium, TruncatedFreeFlightsLandInTheSegmentWithTheirPdf) {
  // Mean of the truncated exponential on [0, d]: 1/s - d e^{-sd} / (1 - e^{-sd}).
  for (float s : {0.0f, 1e-6f, 0.7f, 5.0f, 1e30f}) {
    for (float d : {0.5f, 3.0f, kInf}) {
      Rng rng(31);
      double sum = 0.0, sumSq = 0.0;
      const int n = 100000;
      for (int k = 0; k < n; ++k) {
        const DistanceSample x = sampleTruncatedFreeFlight(s, d, rng.uniform());
        if (s == 0.0f && d == kInf) {
          ASSERT_EQ(x.pdf, 0.0f);  // no proper density: no sample
          continue;
        }
        ASSERT_TRUE(x.t >= 0.0f && x.t <= d && x.pdf > 0.0f && std::isfinite(x.pdf)) << s << " " << d;
        ASSERT_NEAR(x.pdf, truncatedFreeFlightPdf(s, d, x.t), 1e-5 * x.pdf);
        sum += x.t, sumSq += double(x.t) * x.t;
      }
      if (s == 0.0f && d == kInf) continue;
      const double sd = double(s) * d, mean = s == 0.0f || sd < 1e-4 ? 0.5 * d
                                             : std::isinf(d) ? 1.0 / s
                                                             : 1.0 / s - d * std::exp(-sd) / -std::expm1(-sd);
      const double stdError = std::sqrt(std::max(0.0, sumSq / n - (sum / n) * (sum / n)) / n);
      EXPECT_NEAR(sum / n, mean, 5.0 * stdError + 1e-6 * mean) << s << " " << d;
    }
  }
}

}  // namespace
}  // namespace penumbra
