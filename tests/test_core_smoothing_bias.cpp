// The bias figure from the gathers' smoothing probes (SmoothingSums) on synthetic
// passes: a known bias in one region is found there at its size, pure noise is reported
// as noise, a bias in a few pixels is not hidden by its own spread, and the bound holds
// what noise hides.
#include "core/error_estimate.h"
#include "core/rng.h"
#include <gtest/gtest.h>
#include <cmath>

namespace penumbra {
namespace {

constexpr int kSide = 64;
constexpr double kSigma = 0.1;

// Pass p's probe: `bias` inside `where`, plus per-pixel noise of sd `sigma` (uniform).
Image probe(int p, uint64_t seed, double bias, const PixelBounds& where, double sigma = kSigma) {
  Image im(kSide, kSide);
  Rng rng(hashKey(seed, uint64_t(p)));
  const double half = sigma * std::sqrt(3.0);
  for (int y = 0; y < kSide; ++y)
    for (int x = 0; x < kSide; ++x)
      for (int ch = 0; ch < 3; ++ch)
        im.pixels[size_t(y) * kSide + x][ch] =
            float((where.contains(x, y) ? bias : 0.0) + (2.0 * rng.uniform() - 1.0) * half);
  return im;
}

// `passes` passes of a flat image with the probes above.
ErrorEstimate estimate(int passes, uint64_t seed, double bias, const PixelBounds& where, double sigma = kSigma) {
  PassSpread spread;
  const Image flat(kSide, kSide);
  for (int p = 0; p < passes; ++p) {
    const Image pr = probe(p, seed, bias, where, sigma);
    spread.add(flat, p, &pr);
  }
  return spread.estimate();
}

// A bias of 0.05 in a 16 x 16 block (a 16th of the image): each product's noise is
// sigma^2 / 8 at 16 passes, so the block's mean square stands ~30 sd out; the figure
// over the image is the bias times the root of the block's share.
TEST(SmoothingBias, ABiasInOneRegionIsFoundThereAtItsSize) {
  const PixelBounds block{16, 32, 40, 56};
  const double bias = 0.05;
  const ErrorEstimate e = estimate(16, 1, bias, block);
  ASSERT_FALSE(e.biasWithinNoise) << describeError(e);
  EXPECT_TRUE(e.biasFromGathers);
  EXPECT_EQ(e.biasHalf, 0);
  EXPECT_EQ(e.biasRegion, block);
  EXPECT_GT(e.biasRegionShare, 0.9);
  EXPECT_NEAR(e.lightingBiasRmse, bias / 4.0, 0.1 * bias / 4.0);
  EXPECT_GE(e.lightingBiasBound, e.lightingBiasRmse);
  EXPECT_NE(describeError(e).find("the gathers' smoothing"), std::string::npos) << describeError(e);
}

// Pure noise: at most a few frames of 100 hold a cell that stands out, and then at a
// small share of the noise; the bound covers the true 0.
TEST(SmoothingBias, NoiseAloneIsReportedAsNoise) {
  int biased = 0;
  for (uint64_t seed = 1; seed <= 100; ++seed) {
    const ErrorEstimate e = estimate(12, seed, 0.0, {});
    EXPECT_GE(e.lightingBiasBound, 0.0);
    if (!e.biasWithinNoise) {
      ++biased;
      EXPECT_LT(e.lightingBiasRmse, 0.3 * kSigma / std::sqrt(12.0)) << describeError(e);
    }
  }
  EXPECT_LE(biased, 6);
}

// A bias in 4 x 4 pixels, inside one cell of the 8 x 8 grid: one block of it. The
// blocks' own spread, which the bias itself inflates, would hide it; the noise reference
// does not.
TEST(SmoothingBias, ABiasInAFewPixelsIsNotHiddenByItsOwnSpread) {
  const PixelBounds spot{20, 24, 8, 12};
  const double bias = 0.1;
  const ErrorEstimate e = estimate(16, 3, bias, spot);
  ASSERT_FALSE(e.biasWithinNoise) << describeError(e);
  EXPECT_NEAR(e.lightingBiasRmse, bias / 16.0, 0.2 * bias / 16.0);
  EXPECT_TRUE(e.biasRegion.contains(spot.x0, spot.y0));
}

// Noise far above a small bias: the figure counts only what stands out (nothing), and
// the bound, over many frames, holds the true figure in nearly all of them.
TEST(SmoothingBias, TheBoundHoldsWhatNoiseHides) {
  const double bias = 0.01, truth = bias;  // everywhere
  int held = 0;
  for (uint64_t seed = 1; seed <= 50; ++seed) {
    const ErrorEstimate e = estimate(8, seed, bias, PixelBounds::frame(kSide, kSide), 0.5);
    held += e.lightingBiasBound >= truth;
  }
  EXPECT_GE(held, 45);
}

// A merge computes the figure from the sums a tile keeps: the same, to the bit.
TEST(SmoothingBias, TheSumsGiveTheSameFigureAfterAMerge) {
  PassSpread spread;
  const Image flat(kSide, kSide);
  for (int p = 0; p < 10; ++p) {
    const Image pr = probe(p, 9, 0.05, {0, 32, 0, 64});
    spread.add(probe(p, 10, 0.0, {}), p, &pr);
  }
  const ErrorEstimate whole = spread.estimate();
  const ErrorEstimate merged =
      PassSpread::fromHalves(spread.evenSum(), spread.oddSum(), 10, spread.checkpoint(), spread.smoothingSums(), {});
  EXPECT_EQ(describeError(whole), describeError(merged));
  EXPECT_EQ(whole.lightingBiasRmse, merged.lightingBiasRmse);
  EXPECT_EQ(whole.lightingBiasBound, merged.lightingBiasBound);
}

}  // namespace
}  // namespace penumbra
