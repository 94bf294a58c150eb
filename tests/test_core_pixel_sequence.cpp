// sobol02, the pixel sequence of progressive passes: its first points are Sobol's,
// every aligned run of 2^k points puts one point in each elementary cell of area 2^-k
// (all 2^a x 2^(k-a) grids) whatever the scramble, and over random scrambles a point
// is uniform in the square.
#include "core/rng.h"
#include "core/sampling.h"
#include <gtest/gtest.h>
#include <cmath>
#include <set>
#include <utility>

namespace penumbra {
namespace {

TEST(PixelSequence, UnscrambledStartIsSobols) {
  const Vec2 want[4] = {{0.0f, 0.0f}, {0.5f, 0.5f}, {0.25f, 0.75f}, {0.75f, 0.25f}};
  for (uint32_t i = 0; i < 4; ++i) {
    const Vec2 p = sobol02(i, 0);
    EXPECT_EQ(p.x, want[i].x) << i;
    EXPECT_EQ(p.y, want[i].y) << i;
  }
}

TEST(PixelSequence, AlignedRunsAreElementaryNets) {
  // Runs of 2^k points starting at multiples of 2^k, for k = 0..10, three scrambles:
  // each of the k + 1 grids of 2^k cells holds exactly one point per cell.
  Rng rng(hashKey(7, 1));
  for (int trial = 0; trial < 3; ++trial) {
    const uint64_t scramble = (uint64_t(rng.nextU32()) << 32) ^ rng.nextU32();
    for (int k = 0; k <= 10; ++k) {
      const uint32_t n = 1u << k;
      for (uint32_t start : {0u, n, 5u * n, 1000u * n}) {
        for (int a = 0; a <= k; ++a) {
          std::set<std::pair<uint32_t, uint32_t>> cells;
          for (uint32_t i = start; i < start + n; ++i) {
            const Vec2 p = sobol02(i, scramble);
            ASSERT_GE(p.x, 0.0f);
            ASSERT_LT(p.x, 1.0f);
            ASSERT_GE(p.y, 0.0f);
            ASSERT_LT(p.y, 1.0f);
            cells.insert({static_cast<uint32_t>(p.x * float(1u << a)),
                          static_cast<uint32_t>(p.y * float(1u << (k - a)))});
          }
          ASSERT_EQ(cells.size(), n) << "k " << k << " start " << start << " grid 2^" << a << " x 2^" << (k - a);
        }
      }
    }
  }
}

TEST(PixelSequence, ARandomlyScrambledPointIsUniform) {
  // Point 3 under 40000 random scrambles, binned on an 8 x 8 grid: each cell expects
  // 625 (sd 24.8); all within 5 sd.
  Rng rng(hashKey(7, 2));
  constexpr int kDraws = 40000, kSide = 8;
  int counts[kSide][kSide] = {};
  for (int d = 0; d < kDraws; ++d) {
    const uint64_t scramble = (uint64_t(rng.nextU32()) << 32) ^ rng.nextU32();
    const Vec2 p = sobol02(3, scramble);
    ++counts[static_cast<int>(p.x * kSide)][static_cast<int>(p.y * kSide)];
  }
  const double expected = double(kDraws) / (kSide * kSide), sd = std::sqrt(expected * (1.0 - 1.0 / (kSide * kSide)));
  for (int x = 0; x < kSide; ++x) {
    for (int y = 0; y < kSide; ++y) EXPECT_NEAR(counts[x][y], expected, 5.0 * sd) << x << "," << y;
  }
}

}  // namespace
}  // namespace penumbra
