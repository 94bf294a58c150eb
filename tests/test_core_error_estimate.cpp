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

// Where a synthetic drift sits: the pixels x in [x0, x1), y in [y0, y1).
struct Drift {
  double size = 0.0;
  int passes = 0;  // the first `passes` passes have it
  PixelBounds where = PixelBounds::frame(kSide, kSide);
};

// Pass p of a flat grey image with per-pixel noise: uniform of sd kSigma, plus the
// drift's size in its first passes and pixels.
Image noisyPass(int p, const Drift& drift = {}) {
  Image im(kSide, kSide);
  Rng rng(hashKey(7, uint64_t(p)));
  const double half = kSigma * std::sqrt(3.0);  // uniform on [-half, half] has sd kSigma
  for (int y = 0; y < kSide; ++y)
    for (int x = 0; x < kSide; ++x) {
      const double shift = p < drift.passes && drift.where.contains(x, y) ? drift.size : 0.0;
      for (int ch = 0; ch < 3; ++ch) im.pixels[size_t(y) * kSide + x][ch] = float(0.5 + shift + (2.0 * rng.uniform() - 1.0) * half);
    }
  return im;
}

PassSpread addPasses(int n, const Drift& drift = {}, EmitterMask mask = {}) {
  PassSpread spread;
  spread.setEmitterMask(std::move(mask));
  for (int p = 0; p < n; ++p) spread.add(noisyPass(p, drift), p);
  return spread;
}

TEST(ErrorEstimate, NoiseOfPPassesIsSigmaOverRootP) {
  // 12288 pixel channels, each with one difference of the even and odd passes' means:
  // the estimated variance's relative sd is sqrt(2 / 12288) = 1.3%, so the RMSE's is
  // 0.64%; tolerance 4 sd.
  for (int passes : {2, 8, 32}) {
    const ErrorEstimate e = addPasses(passes).estimate();
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
  const PassSpread spread = addPasses(kPasses);
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

// The bias check at 16 passes compares 1-8 with 9-16: the even passes' drift times the
// odd passes', each a difference of two means of 4 passes (sd sigma / sqrt(2) per
// pixel channel), so a product's sd is sigma^2 / 2 and the mean over n channels has sd
// sigma^2 / (2 sqrt(n)).
TEST(ErrorEstimate, NoDriftIsNoise) {
  const ErrorEstimate none = addPasses(16).estimate();
  EXPECT_EQ(none.biasHalf, 8);
  EXPECT_TRUE(none.biasWithinNoise) << describeError(none);
  // 12288 channels: the mean square's sd is 0.0045 sigma^2, so its root stays below
  // 0.1 sigma unless the mean is 2.2 sd high.
  EXPECT_LT(none.lightingBiasRmse, 0.1 * kSigma);
  EXPECT_TRUE(none.biasRegion.empty());
  EXPECT_NE(describeError(none).find("agree within noise"), std::string::npos) << describeError(none);
}

// Photon noise is nearly the same in R, G and B, and neighbours share photons: noise
// that is one grey value over each 4 x 4 pixels is still no bias. A cell's standard
// error from its blocks' spread makes a cell of pure noise pass kBiasSignificance with
// the tail's chance, about 1.4% of frames of 64 cells (a simulation of the products'
// t statistic); counting a pixel's channels and neighbours as independent draws made
// most such frames hold a "biased" cell. 100 frames: at most 6 may.
TEST(ErrorEstimate, NoiseSharedByChannelsAndNeighboursIsNoBias) {
  constexpr int kWide = 256, kShared = 4, kFrames = 100;
  int biased = 0;
  for (uint64_t seed = 1; seed <= kFrames; ++seed) {
    PassSpread spread;
    for (int p = 0; p < 16; ++p) {
      Image im(kWide, kWide);
      Rng rng(hashKey(seed, uint64_t(p)));
      std::vector<float> shared(size_t(kWide / kShared) * (kWide / kShared));
      for (float& v : shared) v = float(0.5 + (2.0 * rng.uniform() - 1.0) * kSigma * std::sqrt(3.0));
      for (int y = 0; y < kWide; ++y)
        for (int x = 0; x < kWide; ++x) im.pixels[size_t(y) * kWide + x] = Color(shared[size_t(y / kShared) * (kWide / kShared) + x / kShared]);
      spread.add(im, p);
    }
    const ErrorEstimate e = spread.estimate();
    if (!e.biasWithinNoise) {
      ++biased;
      EXPECT_LT(e.lightingBiasRmse, 0.3 * e.lightingNoiseRmse) << "seed " << seed << ": " << describeError(e);
    }
  }
  EXPECT_LE(biased, 6) << "of " << kFrames << " frames of pure noise";
}

TEST(ErrorEstimate, ADriftEverywhereIsMeasuredAsBias) {
  const double drift = 0.05;
  const ErrorEstimate some = addPasses(16, {drift, 8}).estimate();
  // The mean square's sd is 0.0045 sigma^2 = 0.18 drift^2 / 4: the root is within 3%.
  EXPECT_NEAR(some.lightingBiasRmse, drift, 0.05 * drift);
  EXPECT_EQ(some.biasRmse, some.lightingBiasRmse) << "no emitter pixels";
  EXPECT_FALSE(some.biasWithinNoise);
}

// A drift in a 16 x 16 block (two by two cells of the 8 x 8 grid) of a 64 x 64 image:
// the region is that block and holds nearly all of it (each cell's sum stands 14 sd out
// of its noise); the figure over the image is the drift times the block's root share
// (1/4), within the noise's 0.0045 sigma^2 on the mean square (7% of the drift's
// 0.1^2 / 16 here: 3.6% on the root; tolerance 10%).
TEST(ErrorEstimate, ADriftInOneRegionIsFoundThere) {
  const double drift = 0.1;
  const PixelBounds block{16, 32, 40, 56};
  const ErrorEstimate e = addPasses(16, {drift, 8, block}).estimate();
  ASSERT_FALSE(e.biasWithinNoise) << describeError(e);
  EXPECT_EQ(e.biasRegion, block) << e.biasRegion.x0 << "," << e.biasRegion.x1 << "," << e.biasRegion.y0 << ","
                                 << e.biasRegion.y1;
  EXPECT_GT(e.biasRegionShare, 0.9);
  EXPECT_NEAR(e.biasRegionArea, 1.0 / 16.0, 1e-12);
  EXPECT_NEAR(e.lightingBiasRmse, drift / 4.0, 0.1 * drift / 4.0);
  EXPECT_NE(describeError(e).find("in x 16-31, y 40-55, 6% of the image"), std::string::npos) << describeError(e);
}

// The bias view: the mean product over 5 x 5 pixels has sd sigma^2 / 10 = 0.001 per
// channel, against a drift of 0.08 (0.0064 squared) in the block: inside, the root is
// within 10% of the drift (2 pixels in from the block's edge); outside, the root of a
// clamped mean of noise averages ~0.013.
TEST(ErrorEstimate, TheBiasViewShowsWhereTheDriftIs) {
  const double drift = 0.08;
  const PixelBounds block{16, 32, 40, 56}, inner{18, 30, 42, 54};
  const Image view = addPasses(16, {drift, 8, block}).bias();
  double inside = 0.0, outside = 0.0;
  for (int y = 0; y < kSide; ++y)
    for (int x = 0; x < kSide; ++x) {
      const float v = view.pixels[size_t(y) * kSide + x].r;
      if (inner.contains(x, y)) inside += v;
      if (!block.contains(x, y)) outside += v;
    }
  EXPECT_NEAR(inside / double(inner.pixels()), drift, 0.1 * drift);
  EXPECT_LT(outside / double(kSide * kSide - block.pixels()), 0.25 * drift);
}

// Pixels that see an emitter are no lighting: a drift there (an emitter's edge) is no
// bias, and the lighting's noise leaves them out.
TEST(ErrorEstimate, EmitterPixelsAreLeftOutOfTheLighting) {
  const PixelBounds lamp{0, 64, 0, 16};
  EmitterMask mask(kSide * kSide, 0);
  for (int y = lamp.y0; y < lamp.y1; ++y)
    for (int x = 0; x < kSide; ++x) mask[size_t(y) * kSide + x] = 1;
  const ErrorEstimate e = addPasses(16, {0.5, 8, lamp}, mask).estimate();
  EXPECT_TRUE(e.biasWithinNoise) << describeError(e);
  EXPECT_NEAR(e.emitterShare, 0.25, 1e-12);
  EXPECT_NEAR(e.lightingNoiseRmse, kSigma / 4.0, 0.03 * kSigma / 4.0);
  EXPECT_NEAR(addPasses(16, {}, mask).estimate().noiseRmse, e.noiseRmse, 1e-5 * e.noiseRmse) << "the drift is not noise";
}

// A sharp edge under stratified samples: each sequence's first half lands on one side
// and its second half on the other (its halves differ by a sign the pixel draws, independently
// for the two sequences), while the whole is exact. The halves of the image differ far
// beyond independent noise; the product of the sequences' drifts has mean 0.
TEST(ErrorEstimate, StrataThatAlternateBetweenHalvesAreNoBias) {
  PassSpread spread;
  constexpr int kPasses = 16;
  for (int p = 0; p < kPasses; ++p) {
    Image im(kSide, kSide);
    for (size_t i = 0; i < im.pixels.size(); ++i) {
      const double side = Rng(hashKey(11, i, uint64_t(p % 2))).uniform() < 0.5 ? 1.0 : -1.0;
      const double shift = (p < kPasses / 2 ? 0.3 : -0.3) * side;
      im.pixels[i] = Color(float(0.5 + shift));
    }
    spread.add(im, p);
  }
  const ErrorEstimate e = spread.estimate();
  // Products of +-0.6^2 with random signs: the mean over 4096 pixels (3 equal channels)
  // has sd 0.36 / 64 = 0.0056, its root below 0.15 at 4 sd.
  EXPECT_LT(e.lightingBiasRmse, 0.15) << describeError(e);
  EXPECT_TRUE(e.biasWithinNoise) << describeError(e);
}

TEST(ErrorEstimate, OnePassIsUnknownAndSamplesGiveTheirStandardError) {
  EXPECT_FALSE(addPasses(1).estimate().known());
  EXPECT_LT(addPasses(3).estimate().biasRmse, 0.0) << "the bias needs 4 passes";
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
