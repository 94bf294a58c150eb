// The photon maps' storage order: coarse Morton keys and the radix sort by key,
// checked against mortonCode63 and std::stable_sort (the definitions they replace).
#include "gather/morton.h"
#include "core/rng.h"
#include <gtest/gtest.h>
#include <tbb/global_control.h>
#include <algorithm>
#include <numeric>

namespace penumbra {
namespace {

PhotonArray<ShadowPhoton> randomShadowPhotons(size_t n, uint16_t lights, uint64_t seed) {
  Rng rng(seed);
  PhotonArray<ShadowPhoton> p(n);
  for (size_t i = 0; i < n; ++i) {
    // Some duplicates on purpose: equal keys must keep their input order.
    const Vec3 pos = i % 7 == 0 && i > 0 ? p[i - 1].position
                                         : Vec3(rng.uniform(), rng.uniform() * 2.0f - 1.0f, rng.uniform() * 5.0f);
    p[i] = {pos, static_cast<uint32_t>(i), static_cast<uint16_t>(rng.uniform() * lights), kDirect};
  }
  return p;
}

TEST(StorageOrder, KeysAreTheTopBitsOfTheMortonCodeUnderTheLightIndex) {
  PhotonArray<ShadowPhoton> p = randomShadowPhotons(5000, 3, 11);
  const PositionView pos = positionsOf(p);
  const Bounds b = computeBounds(pos);
  const StorageKeys keys = storageKeys(pos, &p[0].light, sizeof(ShadowPhoton), true, b);
  ASSERT_EQ(keys.bits, 18 + 2);  // 6 bits per axis, 2 bits for 3 lights
  for (size_t i = 0; i < p.size(); ++i) {
    const uint32_t cell = static_cast<uint32_t>(mortonCode63(p[i].position, b) >> (63 - 18));
    ASSERT_EQ(keys.keys[i], uint32_t(p[i].light) << 18 | cell) << i;
  }
  // Not spatial: the light alone.
  const StorageKeys byLight = storageKeys(pos, &p[0].light, sizeof(ShadowPhoton), false, b);
  EXPECT_EQ(byLight.bits, 2);
  for (size_t i = 0; i < p.size(); ++i) ASSERT_EQ(byLight.keys[i], p[i].light);
}

// One and two radix passes (one light: 18 key bits in 2 x 9; 300 lights: 9 light bits
// over 4 bits per axis, 21 in 11 + 10), across many 65,536-record chunks.
void expectStableSortByKey(size_t n, uint16_t lights, bool spatial) {
  PhotonArray<ShadowPhoton> p = randomShadowPhotons(n, lights, n + lights);
  const PositionView pos = positionsOf(p);
  StorageKeys keys = storageKeys(pos, &p[0].light, sizeof(ShadowPhoton), spatial, computeBounds(pos));
  std::vector<size_t> expected(n);
  std::iota(expected.begin(), expected.end(), size_t(0));
  std::stable_sort(expected.begin(), expected.end(),
                   [&](size_t a, size_t b) { return keys.keys[a] < keys.keys[b]; });
  const std::vector<uint32_t> before = keys.keys;
  PhotonArray<ShadowPhoton> sorted = p;
  sortByKey(sorted, keys);
  ASSERT_EQ(sorted.size(), n);
  for (size_t i = 0; i < n; ++i) {
    // The normal field carries the input index: the exact stable order, ties included.
    ASSERT_EQ(sorted[i].normal, p[expected[i]].normal) << i;
    ASSERT_EQ(keys.keys[i], before[expected[i]]) << i;  // the keys travel along
  }
}

TEST(StorageOrder, RadixSortEqualsAStableSortByKey) {
  expectStableSortByKey(300000, 1, true);    // 18 bits: two passes of 9
  expectStableSortByKey(200000, 300, true);  // 9 light bits + 12 cell bits: 11 + 10
  expectStableSortByKey(100000, 5, false);   // 3 bits: one pass
  expectStableSortByKey(1, 1, true);
  expectStableSortByKey(0, 1, true);
}

TEST(StorageOrder, TheOrderDoesNotDependOnTheThreadCount) {
  PhotonArray<ShadowPhoton> p = randomShadowPhotons(250000, 2, 5);
  auto sortedWith = [&](int threads) {
    tbb::global_control limit(tbb::global_control::max_allowed_parallelism, threads);
    PhotonArray<ShadowPhoton> q = p;
    const PositionView pos = positionsOf(q);
    StorageKeys keys = storageKeys(pos, &q[0].light, sizeof(ShadowPhoton), true, computeBounds(pos));
    sortByKey(q, keys);
    return q;
  };
  const PhotonArray<ShadowPhoton> one = sortedWith(1), two = sortedWith(2);
  for (size_t i = 0; i < p.size(); ++i) ASSERT_EQ(one[i].normal, two[i].normal) << i;
}

}  // namespace
}  // namespace penumbra
