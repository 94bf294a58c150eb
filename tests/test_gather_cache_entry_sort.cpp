// The lookup cache's entry sort against std::stable_sort by key (the order the cache's
// records and their photons were defined in): few cells with many repeats across radix
// chunks, keys over every bit of the layout, one key, and the empty and single cases.
#include "gather/lookup_cache/lookup_cache_cells.h"
#include "gather/radix_pass.h"
#include "core/rng.h"
#include <gtest/gtest.h>
#include <tbb/global_control.h>
#include <algorithm>

namespace penumbra {
namespace {

uint64_t cellKey(uint64_t x, uint64_t y, uint64_t z, uint64_t bucket) { return x << 44 | y << 24 | z << 4 | bucket; }

// n entries in (source, index) order, as LookupCache::build makes them, whose cells
// lie in a box `side` cells wide from `lo` on every axis.
PhotonArray<CacheEntry> entriesIn(size_t n, uint64_t lo, uint64_t side, uint64_t seed) {
  Rng rng(seed);
  PhotonArray<CacheEntry> e(n);
  auto axis = [&] { return lo + std::min<uint64_t>(side - 1, static_cast<uint64_t>(rng.uniform() * side)); };
  for (size_t i = 0; i < n; ++i) {
    const uint64_t bucket = std::min<uint64_t>(15, static_cast<uint64_t>(rng.uniform() * 16));
    e[i] = {cellKey(axis(), axis(), axis(), bucket), static_cast<uint32_t>(i % 1000), static_cast<uint32_t>(i / 1000)};
  }
  return e;
}

void expectStableOrder(PhotonArray<CacheEntry> e) {
  PhotonArray<CacheEntry> want = e;
  std::stable_sort(want.begin(), want.end(), [](const CacheEntry& a, const CacheEntry& b) { return a.key < b.key; });
  sortCacheEntries(e);
  ASSERT_EQ(e.size(), want.size());
  for (size_t i = 0; i < e.size(); ++i) {
    ASSERT_EQ(e[i].key, want[i].key) << i;
    ASSERT_EQ(e[i].source, want[i].source) << i;
    ASSERT_EQ(e[i].index, want[i].index) << i;
  }
}

TEST(CacheEntrySort, FewCellsManyRepeatsAcrossChunksKeepTheirOrder) {
  // 5 cells a side and 16 buckets: ~2000 keys over 3.3 radix chunks, ~100 entries each.
  expectStableOrder(entriesIn(3 * kRadixChunk + 17, 7, 5, 1));
}

TEST(CacheEntrySort, KeysOverEveryBitOfTheLayoutSortInSixPasses) {
  // Cells anywhere in the 2^20 a side: 64 key bits, six 11-bit digits.
  expectStableOrder(entriesIn(50000, 0, uint64_t(1) << 20, 2));
  // A box far from the origin: the high bits of every axis are set in all keys.
  expectStableOrder(entriesIn(50000, (uint64_t(1) << 20) - 300, 300, 3));
}

TEST(CacheEntrySort, OneKeyAndTinyInputsAreLeftInOrder) {
  expectStableOrder(entriesIn(1000, 12, 1, 4));
  expectStableOrder({});
  expectStableOrder(entriesIn(1, 3, 4, 5));
  expectStableOrder(entriesIn(2, 3, 4, 6));
}

TEST(CacheEntrySort, OneThreadSortsAlike) {
  const PhotonArray<CacheEntry> e = entriesIn(2 * kRadixChunk + 5, 0, 40, 7);
  PhotonArray<CacheEntry> one = e, many = e;
  {
    tbb::global_control single(tbb::global_control::max_allowed_parallelism, 1);
    sortCacheEntries(one);
  }
  sortCacheEntries(many);
  for (size_t i = 0; i < e.size(); ++i) ASSERT_TRUE(one[i].key == many[i].key && one[i].source == many[i].source && one[i].index == many[i].index) << i;
}

}  // namespace
}  // namespace penumbra
