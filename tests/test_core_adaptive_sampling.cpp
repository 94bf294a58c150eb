// Adaptive pixel sampling's rule (closed-form counts, the cap) and the honesty of the
// two-set error estimate under it: synthetic passes whose pixels' noise is known, the
// later passes sampled as the rule says, estimate against the measured error.
#include "core/adaptive_sampling.h"
#include "core/error_estimate.h"
#include "core/rng.h"
#include <gtest/gtest.h>
#include <cmath>
#include <vector>

namespace penumbra {
namespace {

Image grey(std::vector<float> values) {
  Image out(int(values.size()), 1);
  for (size_t i = 0; i < values.size(); ++i) out.pixels[i] = Color(values[i]);
  return out;
}

TEST(AdaptiveRule, SamplesInProportionToTheErrorAboveTheThreshold) {
  std::vector<uint16_t> extra;
  // threshold 2 x RMSE 0.1: u = 0.2; 0.5 / 0.2 = 2.5 -> ceil(2.5 spp) in all.
  const AdaptiveRule rule{2.0, 1, 16};
  EXPECT_EQ(adaptiveExtras(grey({0.1f, 0.19f, 0.21f, 0.5f, 100.0f}), 0.1, rule, extra), 0u + 0 + 1 + 2 + 15);
  EXPECT_EQ(extra, (std::vector<uint16_t>{0, 0, 1, 2, 15}));  // below u: none; far above: the cap, 16 in all
  adaptiveExtras(grey({0.5f, 0.29f}), 0.1, {2.0, 2, 16}, extra);
  EXPECT_EQ(extra, (std::vector<uint16_t>{3, 1}));  // ceil(2 x 2.5) = 5, ceil(2 x 1.45) = 3
  // The error is the RMS over channels: (0.6, 0, 0) is 0.346 -> ceil(1.73) = 2.
  Image one(1, 1);
  one.pixels[0] = Color(0.6f, 0.0f, 0.0f);
  adaptiveExtras(one, 0.1, rule, extra);
  EXPECT_EQ(extra[0], 1);
  // A cap at spp, no image error, or a NaN error: nobody takes more.
  EXPECT_EQ(adaptiveExtras(grey({5.0f}), 0.1, {2.0, 4, 4}, extra), 0u);
  EXPECT_EQ(adaptiveExtras(grey({5.0f}), 0.0, rule, extra), 0u);
  EXPECT_EQ(adaptiveExtras(grey({std::nanf("")}), 0.1, rule, extra), 0u);
}

// A standard normal from two uniforms (Box-Muller), keyed so the test is the same everywhere.
double gaussian(Rng& rng) {
  const double u = 1.0 - rng.uniform(), v = rng.uniform();
  return std::sqrt(-2.0 * std::log(u)) * std::cos(6.283185307179586 * v);
}

struct Outcome {
  double estimate, measured;
  uint64_t samples;
};

// 12 passes over 20000 pixels of true value 0: each pass adds photon noise (sd 0.5,
// which samples do not reduce) and the mean of its camera samples' noise (sd 1, or 12
// at 1% of the pixels: the caustic edge). From pass 2 on the rule sets the samples.
Outcome simulate(bool adaptive) {
  const int pixels = 20000, passes = 12;
  const AdaptiveRule rule{4.0, 1, 16};
  PassSpread spread;
  Image sum(pixels, 1);
  std::vector<uint16_t> extra(pixels, 0);
  uint64_t samples = 0;
  for (int pass = 0; pass < passes; ++pass) {
    if (adaptive && pass >= kAdaptiveFirstPass) adaptiveExtras(spread.standardError(), spread.estimate().noiseRmse, rule, extra);
    Image image(pixels, 1);
    for (int i = 0; i < pixels; ++i) {
      Rng rng(hashKey(7, uint64_t(i), uint64_t(pass)));
      const double sd = i % 100 == 0 ? 12.0 : 1.0;
      const int n = 1 + extra[size_t(i)];
      samples += uint64_t(n);
      for (int c = 0; c < 3; ++c) image.pixels[size_t(i)][c] = float(0.5 * gaussian(rng) + sd / std::sqrt(double(n)) * gaussian(rng));
    }
    spread.add(image, pass);
    for (int i = 0; i < pixels; ++i) sum.pixels[size_t(i)] += image.pixels[size_t(i)];
  }
  double squares = 0.0;
  for (const Color& c : sum.pixels) {
    for (int k = 0; k < 3; ++k) squares += double(c[k] / passes) * (c[k] / passes);
  }
  return {spread.estimate().noiseRmse, std::sqrt(squares / (3.0 * pixels)), samples};
}

TEST(AdaptiveRule, TheTwoSetEstimateStaysTheMeasuredError) {
  const Outcome uniform = simulate(false), adaptive = simulate(true);
  std::printf("uniform: estimate %.4f measured %.4f (%llu samples); adaptive: estimate %.4f measured %.4f (%llu)\n",
              uniform.estimate, uniform.measured, (unsigned long long)uniform.samples, adaptive.estimate,
              adaptive.measured, (unsigned long long)adaptive.samples);
  // Closed form, uniform: sqrt((0.25 + 0.99 + 0.01 x 144) / 12) = 0.4726.
  EXPECT_NEAR(uniform.measured, 0.4726, 0.01);
  EXPECT_NEAR(uniform.estimate / uniform.measured, 1.0, 0.05);
  EXPECT_NEAR(adaptive.estimate / adaptive.measured, 1.0, 0.05);
  // The noisy pixels' samples pay: less error for a few percent more samples.
  EXPECT_LT(adaptive.measured, 0.92 * uniform.measured);
  EXPECT_LT(double(adaptive.samples), 1.10 * double(uniform.samples));
}

}  // namespace
}  // namespace penumbra
