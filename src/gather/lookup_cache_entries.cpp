// The lookup cache's photon entries in key order: a stable radix sort over the bits of
// the cell coordinates and bucket the photons occupy (a few cells a side, not 2^20).
#include "gather/lookup_cache_cells.h"
#include "gather/radix_pass.h"
#include <tbb/blocked_range.h>
#include <tbb/parallel_reduce.h>

namespace penumbra {

namespace {

// A key (LookupCache::keyOf: x << 44 | y << 24 | z << 4 | bucket, 20 bits an axis)
// packed densely, given each axis's width: the same order on the keys that occur.
struct DenseKey {
  int yShift = 0, xShift = 0;
  uint64_t operator()(uint64_t key) const {
    constexpr uint64_t kAxis = (uint64_t(1) << 20) - 1;
    return (key >> 44) << xShift | (key >> 24 & kAxis) << yShift | (key & ((kAxis << 4) | 15u));
  }
};

// How many bits v needs (0 for 0).
int bitWidth(uint64_t v) { return v ? 64 - __builtin_clzll(v) : 0; }

}  // namespace

void sortCacheEntries(PhotonArray<CacheEntry>& entries) {
  const size_t n = entries.size();
  if (n < 2) return;
  // Each field's width is that of the OR of all its values.
  const uint64_t used = tbb::parallel_reduce(
      tbb::blocked_range<size_t>(0, n, kRadixChunk), uint64_t(0),
      [&](const tbb::blocked_range<size_t>& r, uint64_t acc) {
        for (size_t i = r.begin(); i != r.end(); ++i) acc |= entries[i].key;
        return acc;
      },
      [](uint64_t a, uint64_t b) { return a | b; });
  constexpr uint64_t kAxis = (uint64_t(1) << 20) - 1;
  const int zBits = bitWidth(used >> 4 & kAxis), yBits = bitWidth(used >> 24 & kAxis);
  const int xBits = bitWidth(used >> 44);
  DenseKey dense;
  dense.yShift = 4 + zBits;
  dense.xShift = dense.yShift + yBits;
  const int bits = dense.xShift + xBits;
  // Balanced digits of at most kMaxRadixDigitBits, least significant first.
  const int passes = (bits + kMaxRadixDigitBits - 1) / kMaxRadixDigitBits;
  const int digitBits = (bits + passes - 1) / passes;
  const uint64_t mask = (uint64_t(1) << digitBits) - 1;
  PhotonArray<CacheEntry> other(n);  // every element written by the first pass
  for (int pass = 0; pass < passes; ++pass) {
    const int shift = pass * digitBits;
    const CacheEntry* src = entries.data();
    CacheEntry* dst = other.data();
    radixScatter(
        ArraySource<CacheEntry>{src}, n, digitBits, [&](size_t i) { return dense(src[i].key) >> shift & mask; },
        [&](size_t at, size_t, const CacheEntry& e) { dst[at] = e; });
    entries.swap(other);
  }
}

}  // namespace penumbra
