// permutationElement (core/permutation.h): a bijection on [0, n) for every n up to 1024
// and every seed tried (the top of the seed range included, where i + seed wraps), and
// element i uniform over seeds.
#include "core/permutation.h"
#include <gtest/gtest.h>
#include <cmath>
#include <vector>

namespace penumbra {
namespace {

TEST(Permutation, EveryElementOnceForEveryCountAndSeed) {
  const std::vector<uint32_t> seeds = {0u, 1u, 7u, 0x9e3779b9u, 0x7fffffffu, 0xfffffc00u, 0xfffffffeu, 0xffffffffu};
  std::vector<int> seen;
  for (uint32_t n = 1; n <= 1024; ++n) {
    for (uint32_t seed : seeds) {
      seen.assign(n, 0);
      for (uint32_t i = 0; i < n; ++i) {
        const uint32_t e = permutationElement(i, n, seed);
        ASSERT_LT(e, n) << "n " << n << " seed " << seed;
        ++seen[e];
      }
      for (uint32_t e = 0; e < n; ++e) ASSERT_EQ(seen[e], 1) << "n " << n << " seed " << seed << " element " << e;
    }
  }
}

// Element 0 of a permutation of 12 over 120000 seeds: each value 10000 times, chi-square
// with 11 degrees of freedom below its 99.9th percentile (31.3).
TEST(Permutation, AnElementIsUniformOverSeeds) {
  const uint32_t n = 12, seeds = 120000;
  std::vector<double> counts(n, 0.0);
  for (uint32_t s = 0; s < seeds; ++s) counts[permutationElement(0, n, s * 2654435761u)] += 1.0;
  double chi2 = 0.0;
  const double expected = double(seeds) / n;
  for (double c : counts) chi2 += (c - expected) * (c - expected) / expected;
  EXPECT_LT(chi2, 31.3);
}

}  // namespace
}  // namespace penumbra
