// Kronecker4, the shadow photons' starts: every prefix of any length spreads evenly
// over the two pairs of numbers a photon uses together (its point on the light, its
// direction), far closer to n/16 per cell than independent points, and over random
// shifts each point is uniform (a chi-square test).
#include "core/rng.h"
#include "core/sampling.h"
#include <gtest/gtest.h>
#include <algorithm>
#include <cmath>
#include <cstdlib>
#include <vector>

namespace penumbra {
namespace {

// Largest |count - n/16| over a 4 x 4 grid of coordinates (a, b) of points 0..n-1.
double worstCell(const Kronecker4& seq, int n, int a, int b) {
  std::vector<int> cells(16, 0);
  for (int i = 0; i < n; ++i) {
    const float x = seq(static_cast<uint64_t>(i), a), y = seq(static_cast<uint64_t>(i), b);
    EXPECT_GE(x, 0.0f);
    EXPECT_LT(x, 1.0f);
    ++cells[static_cast<size_t>(x * 4.0f) + 4 * static_cast<size_t>(y * 4.0f)];
  }
  double worst = 0.0;
  for (int c : cells) worst = std::max(worst, std::abs(c - n / 16.0));
  return worst;
}

// The quad's 16 strata are the 4 x 4 cells of coordinates (0, 1). Independent points
// stray from n/16 by sqrt(n 15/256) in one standard deviation: 15.5 at n = 4096, so
// a worst cell of 16 cells would be about 30 off.
TEST(Kronecker4, EveryPrefixFillsTheLightsStrataAndTheDirectionsEvenly) {
  for (uint64_t shift = 0; shift < 20; ++shift) {
    Rng rng(17, shift);
    const Kronecker4 seq(rng);
    for (int n : {16, 100, 1000, 4096}) {
      EXPECT_LE(worstCell(seq, n, 0, 1), 8.0) << "light point, n " << n << " shift " << shift;
      EXPECT_LE(worstCell(seq, n, 2, 3), 8.0) << "direction, n " << n << " shift " << shift;
    }
  }
}

// Point 1234 over 16000 shifts: each coordinate in 16 bins, chi-square with 15 degrees
// of freedom under 37.7 (p = 0.001).
TEST(Kronecker4, EachPointIsUniformOverShifts) {
  constexpr int kShifts = 16000, kBins = 16;
  std::vector<std::vector<int>> bins(4, std::vector<int>(kBins, 0));
  for (int s = 0; s < kShifts; ++s) {
    Rng rng(29, static_cast<uint64_t>(s));
    const Kronecker4 seq(rng);
    for (int k = 0; k < 4; ++k) ++bins[k][static_cast<size_t>(seq(1234, k) * kBins)];
  }
  const double expected = static_cast<double>(kShifts) / kBins;
  for (int k = 0; k < 4; ++k) {
    double chi2 = 0.0;
    for (int c : bins[k]) chi2 += (c - expected) * (c - expected) / expected;
    EXPECT_LT(chi2, 37.7) << "coordinate " << k;
  }
}

}  // namespace
}  // namespace penumbra
