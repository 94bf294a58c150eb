// The error estimate against synthetic passes of known spread: the noise RMSE of P
// passes of per-pixel noise sigma is sigma / sqrt(P); the per-pixel figure is the
// even and odd passes' formula; a drift between the first and second half of the passes is
// measured as bias, and no drift as none; a samples' variance image gives its RMSE.
#include "core/error_estimate.h"
#include "core/rng.h"
#include <gtest/gtest.h>
#include <cmath>
#include <vector>

namespace penumbra {
namespace {

constexpr int kSide = 64;
constexpr double kSigma = 0.1;

// Pass p of a flat grey image with per-pixel noise: uniform of sd kSigma, plus `drift`
// in the first `driftPasses` passes.
Image noisyPass(int p, double drift = 0.0, int driftPasses = 0) {
  Image im(kSide, kSide);
  Rng rng(hashKey(7, uint64_t(p)));
  const double half = kSigma * std::sqrt(3.0);  // uniform on [-half, half] has sd kSigma
  for (Color& c : im.pixels) {
    for (int ch = 0; ch < 3; ++ch) c[ch] = float(0.5 + (p < driftPasses ? drift : 0.0) + (2.0 * rng.uniform() - 1.0) * half);
  }
  return im;
}

// Adds passes 0..n-1 the way a frame does: spread first, then into the sum.
PassSpread addPasses(int n, Image& sum, double drift = 0.0, int driftPasses = 0) {
  PassSpread spread;
  for (int p = 0; p < n; ++p) {
    const Image x = noisyPass(p, drift, driftPasses);
    spread.add(sum, x, p);
    if (p == 0) sum = x;
    else for (size_t i = 0; i < x.pixels.size(); ++i) sum.pixels[i] += x.pixels[i];
  }
  return spread;
}

TEST(ErrorEstimate, NoiseOfPPassesIsSigmaOverRootP) {
  // 12288 pixel channels, each with one difference of the even and odd passes' means:
  // the estimated variance's relative sd is sqrt(2 / 12288) = 1.3%, so the RMSE's is
  // 0.64%; tolerance 4 sd.
  for (int passes : {2, 8, 32}) {
    Image sum;
    const ErrorEstimate e = addPasses(passes, sum).estimate();
    ASSERT_TRUE(e.known());
    EXPECT_EQ(e.source, ErrorSource::Passes);
    EXPECT_EQ(e.count, passes);
    const double want = kSigma / std::sqrt(double(passes));
    EXPECT_NEAR(e.noiseRmse, want, 4.0 * 0.0064 * want) << passes;
  }
}

// Per pixel: with n_e even and n_o odd passes of P, the mean's variance is
// n_e n_o / P^2 times the difference of their means, squared.
TEST(ErrorEstimate, StandardErrorIsTheEvenAndOddPassesFormula) {
  constexpr int kPasses = 5;
  Image sum;
  const PassSpread spread = addPasses(kPasses, sum);
  const Image se = spread.standardError();
  for (size_t i = 0; i < se.pixels.size(); i += 97) {
    for (int c = 0; c < 3; ++c) {
      double even = 0.0, odd = 0.0;
      for (int p = 0; p < kPasses; p += 2) even += noisyPass(p).pixels[i][c] / 3.0;
      for (int p = 1; p < kPasses; p += 2) odd += noisyPass(p).pixels[i][c] / 2.0;
      EXPECT_NEAR(se.pixels[i][c], std::sqrt(3.0 * 2.0 / 25.0) * std::abs(even - odd), 1e-5) << i;
    }
  }
}

TEST(ErrorEstimate, ADriftBetweenHalvesIsBiasAndNoDriftIsNone) {
  // 16 passes: the check compares 1-8 with 9-16. Noise alone gives the halves' means a
  // difference of sd sigma / 2 per pixel channel; subtracting it leaves a bias
  // estimate whose spread over 12288 channels is ~0.02 x sigma.
  Image flat, drifted;
  const ErrorEstimate none = addPasses(16, flat).estimate();
  EXPECT_EQ(none.biasHalf, 8);
  EXPECT_LT(none.biasRmse, 0.1 * kSigma);
  const double drift = 0.05;
  const ErrorEstimate some = addPasses(16, drifted, drift, 8).estimate();
  EXPECT_NEAR(some.biasRmse, drift, 0.1 * drift);
}

TEST(ErrorEstimate, OnePassIsUnknownAndSamplesGiveTheirStandardError) {
  Image sum;
  EXPECT_FALSE(addPasses(1, sum).estimate().known());
  Image standardError(4, 4);
  for (size_t i = 0; i < standardError.pixels.size(); ++i) standardError.pixels[i] = Color(std::sqrt(i < 8 ? 0.01f : 0.03f));
  const ErrorEstimate e = sampleError(standardError, 16);
  EXPECT_EQ(e.source, ErrorSource::Samples);
  EXPECT_NEAR(e.noiseRmse, std::sqrt(0.02), 1e-7);
  EXPECT_FALSE(sampleError(standardError, 1).known());
  // Errors whose squares overflow float (1e20^2 = 1e40) average in double: finite.
  standardError.pixels.assign(16, Color(1e20f));
  EXPECT_NEAR(sampleError(standardError, 4).noiseRmse, 1e20, 1e20 * 1e-6);
  EXPECT_NE(describeError(e).find("from 16 samples per pixel"), std::string::npos) << describeError(e);
  EXPECT_NE(describeError(ErrorEstimate()).find("unknown"), std::string::npos);
}

TEST(ErrorEstimate, TheTextNamesAPhotonMapOnlyWhereTheSamplesShareOne) {
  ErrorEstimate samples;
  samples.source = ErrorSource::Samples;
  samples.count = 4;
  samples.noiseRmse = 0.01;
  ErrorEstimate probes = samples;
  probes.source = ErrorSource::Probes;
  probes.count = 600;
  for (const ErrorEstimate& e : {samples, probes}) {
    EXPECT_EQ(describeError(e).find("photon map"), std::string::npos) << describeError(e);
    ErrorEstimate withMap = e;
    withMap.sharedMaps = true;
    EXPECT_NE(describeError(withMap).find("photon map, so its noise is not in it"), std::string::npos)
        << describeError(withMap);
  }
  EXPECT_NE(describeError(probes).find("from probes at 600 pixels"), std::string::npos) << describeError(probes);
}

}  // namespace
}  // namespace penumbra
