// The lookup cache's photon entries in key order: a stable radix sort over the bits of
// the cell coordinates and bucket the photons occupy (a few cells a side, not 2^20).
#include "gather/lookup_cache/lookup_cache_cells.h"
#include "gather/radix_pass.h"
#include <tbb/blocked_range.h>
#include <tbb/parallel_reduce.h>

namespace penumbra {

namespace {

// A key's fields (decodeCellKey: x, y, z, then the 4-bit bucket) packed densely, given
// each axis's width: the same order on the keys that occur.
struct DenseKey {
  int yShift = 0, xShift = 0;
  uint64_t operator()(uint64_t key) const {
    const CellKey c = decodeCellKey(key);
    return uint64_t(c.x) << xShift | uint64_t(c.y) << yShift | uint64_t(c.z) << 4 | c.bucket;
  }
};

// How many bits v needs (0 for 0).
int bitWidth(uint64_t v) { return v ? 64 - __builtin_clzll(v) : 0; }

}  // namespace

void sortCacheEntries(PhotonArray<CacheEntry>& entries) {
  const size_t n = entries.size();
  if (n < 2) return;
  // Each field's width is that of the OR of all its values: the fields of the OR.
  const uint64_t used = tbb::parallel_reduce(
      tbb::blocked_range<size_t>(0, n, kRadixChunk), uint64_t(0),
      [&](const tbb::blocked_range<size_t>& r, uint64_t acc) {
        for (size_t i = r.begin(); i != r.end(); ++i) acc |= entries[i].key;
        return acc;
      },
      [](uint64_t a, uint64_t b) { return a | b; });
  const CellKey widest = decodeCellKey(used);
  DenseKey dense;
  dense.yShift = 4 + bitWidth(uint64_t(widest.z));
  dense.xShift = dense.yShift + bitWidth(uint64_t(widest.y));
  const int bits = dense.xShift + bitWidth(uint64_t(widest.x));
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
