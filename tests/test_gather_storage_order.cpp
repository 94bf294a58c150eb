// The photon maps' storage order: coarse Morton keys and the radix sort by key, read
// straight out of an emission's batches, checked against mortonCode63 and
// std::stable_sort over the batches' sequence (the definitions they replace).
#include "gather/morton.h"
#include "core/rng.h"
#include <gtest/gtest.h>
#include <tbb/global_control.h>
#include <algorithm>
#include <cstring>
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
    p[i] = {pos, static_cast<uint32_t>(i), static_cast<uint16_t>(rng.uniform() * lights), kDirect, 0, 0};
  }
  return p;
}

// The photons as an emission would hand them over: uneven batches (some empty) in
// one mapped block, so sequence positions cross batch and chunk boundaries.
PhotonBatches<ShadowPhoton> inBatches(const PhotonArray<ShadowPhoton>& p, uint64_t seed) {
  MappedBlock block(std::max<size_t>(1, p.size()) * sizeof(ShadowPhoton));
  ShadowPhoton* base = static_cast<ShadowPhoton*>(block.data());
  std::copy(p.begin(), p.end(), base);
  std::vector<PhotonBatches<ShadowPhoton>::Span> spans;
  Rng rng(seed);
  for (size_t at = 0; at < p.size();) {
    const size_t n = std::min(p.size() - at, static_cast<size_t>(rng.uniform() * 9000.0f));
    spans.push_back({base + at, n});
    at += n;
  }
  std::vector<MappedBlock> blocks;
  blocks.push_back(std::move(block));
  return PhotonBatches<ShadowPhoton>(std::move(spans), std::move(blocks));
}

TEST(StorageOrder, BatchesReadAsOneSequence) {
  const PhotonArray<ShadowPhoton> p = randomShadowPhotons(70000, 2, 3);
  const PhotonBatches<ShadowPhoton> batches = inBatches(p, 4);
  ASSERT_EQ(batches.size(), p.size());
  EXPECT_GT(batches.batchCount(), 10u);
  size_t i = 0;
  for (const ShadowPhoton& q : batches) ASSERT_EQ(q.normal, p[i++].normal);
  EXPECT_EQ(i, p.size());
  for (size_t j : {size_t(0), size_t(8999), size_t(9000), size_t(69999)}) EXPECT_EQ(batches[j].normal, j);
  size_t visited = 0;
  batches.forRange(12345, 40000, [&](size_t at, const ShadowPhoton& q) {
    ASSERT_EQ(q.normal, at);
    ++visited;
  });
  EXPECT_EQ(visited, 40000u - 12345u);
  EXPECT_EQ(std::memcmp(batches.flatten().data(), p.data(), p.size() * sizeof(ShadowPhoton)), 0);
  // A plain array is one batch, handed back without a copy.
  PhotonArray<ShadowPhoton> q = p;
  const ShadowPhoton* data = q.data();
  PhotonBatches<ShadowPhoton> one(std::move(q));
  EXPECT_EQ(one.batchCount(), 1u);
  EXPECT_EQ(std::move(one).takeArray().data(), data);
}

TEST(StorageOrder, KeysAreTheTopBitsOfTheMortonCodeUnderTheLightIndex) {
  PhotonArray<ShadowPhoton> p = randomShadowPhotons(5000, 3, 11);
  const PhotonBatches<ShadowPhoton> batches = inBatches(p, 1);
  const Bounds b = computeBounds(batches);
  const StorageKeys keys = storageKeys(batches, true, true, b);
  ASSERT_EQ(keys.bits, 18 + 2);  // 6 bits per axis, 2 bits for 3 lights
  for (size_t i = 0; i < p.size(); ++i) {
    const uint32_t cell = static_cast<uint32_t>(mortonCode63(p[i].position, b) >> (63 - 18));
    ASSERT_EQ(keys.keys[i], uint32_t(p[i].light) << 18 | cell) << i;
  }
  // Not spatial: the light alone.
  const StorageKeys byLight = storageKeys(batches, true, false, b);
  EXPECT_EQ(byLight.bits, 2);
  for (size_t i = 0; i < p.size(); ++i) ASSERT_EQ(byLight.keys[i], p[i].light);
}

// One and two radix passes (one light: 18 key bits in 2 x 9; 300 lights: 9 light bits
// over 4 bits per axis, 21 in 11 + 10), across many 65,536-record chunks.
void expectStableSortByKey(size_t n, uint16_t lights, bool spatial) {
  PhotonArray<ShadowPhoton> p = randomShadowPhotons(n, lights, n + lights);
  PhotonBatches<ShadowPhoton> batches = inBatches(p, n);
  StorageKeys keys = storageKeys(batches, true, spatial, computeBounds(batches));
  std::vector<size_t> expected(n);
  std::iota(expected.begin(), expected.end(), size_t(0));
  std::stable_sort(expected.begin(), expected.end(),
                   [&](size_t a, size_t b) { return keys.keys[a] < keys.keys[b]; });
  PhotonArray<ShadowPhoton> sorted = sortByKey(std::move(batches), std::move(keys));
  ASSERT_EQ(sorted.size(), n);
  for (size_t i = 0; i < n; ++i) {
    // The normal field carries the input index: the exact stable order, ties included.
    ASSERT_EQ(sorted[i].normal, p[expected[i]].normal) << i;
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
    PhotonBatches<ShadowPhoton> q = inBatches(p, 9);
    StorageKeys keys = storageKeys(q, true, true, computeBounds(q));
    return sortByKey(std::move(q), std::move(keys));
  };
  const PhotonArray<ShadowPhoton> one = sortedWith(1), two = sortedWith(2);
  for (size_t i = 0; i < p.size(); ++i) ASSERT_EQ(one[i].normal, two[i].normal) << i;
}

}  // namespace
}  // namespace penumbra
