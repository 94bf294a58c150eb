// Morton codes and the deterministic storage order (a coarse spatial counting sort).
#include "gather/morton.h"
#include "gather/radix_pass.h"
#include <tbb/blocked_range.h>
#include <tbb/enumerable_thread_specific.h>
#include <tbb/parallel_for.h>
#include <tbb/parallel_reduce.h>
#include <algorithm>
#include <array>

namespace penumbra {

uint64_t spreadBits21(uint32_t v) {
  uint64_t x = v & 0x1FFFFFu;
  x = (x | (x << 32)) & 0x1F00000000FFFFull;
  x = (x | (x << 16)) & 0x1F0000FF0000FFull;
  x = (x | (x << 8)) & 0x100F00F00F00F00Full;
  x = (x | (x << 4)) & 0x10C30C30C30C30C3ull;
  x = (x | (x << 2)) & 0x1249249249249249ull;
  return x;
}

namespace {
// p's cell on each axis among 2^21 over b; degenerate axes quantise to 0 instead of NaN.
void quantise21(const Vec3& p, const Bounds& b, uint32_t q[3]) {
  constexpr float kCells = 2097151.0f;  // 2^21 - 1
  for (int a = 0; a < 3; ++a) {
    float extent = b.hi[a] - b.lo[a];
    float t = extent > 0.0f ? (p[a] - b.lo[a]) / extent : 0.0f;
    q[a] = static_cast<uint32_t>(std::clamp(t, 0.0f, 1.0f) * kCells);
  }
}
}  // namespace

uint64_t mortonCode63(const Vec3& p, const Bounds& b) {
  uint32_t q[3];
  quantise21(p, b, q);
  return spreadBits21(q[0]) | (spreadBits21(q[1]) << 1) | (spreadBits21(q[2]) << 2);
}

namespace {
// Bit i of a 6-bit value moved to bit 3i: a table, since a loop over the bits
// cost more than the rest of the key.
constexpr std::array<uint32_t, 64> kSpread6 = [] {
  std::array<uint32_t, 64> t{};
  for (uint32_t v = 0; v < 64; ++v)
    for (int bit = 0; bit < 6; ++bit) t[v] |= (v >> bit & 1u) << (3 * bit);
  return t;
}();

// The top `b` (<= 6) bits of each axis's 21-bit quantised coordinate, interleaved:
// exactly mortonCode63(p, bounds) >> (63 - 3b), without spreading the bits it drops.
uint32_t coarseCell(const Vec3& p, const Bounds& bounds, int b) {
  uint32_t q[3];
  quantise21(p, bounds, q);
  return kSpread6[q[0] >> (21 - b)] | kSpread6[q[1] >> (21 - b)] << 1 | kSpread6[q[2] >> (21 - b)] << 2;
}

// One stable counting-sort pass on the digit (key >> shift) & mask, src -> dst,
// carrying the keys along to dstKeys if given.
template <class Photon, class Source>
std::vector<size_t> scatterPass(const Source& src, const uint32_t* srcKeys, Photon* dst, uint32_t* dstKeys,
                                size_t n, int shift, int digitBits) {
  const uint32_t mask = (uint32_t(1) << digitBits) - 1;
  return radixScatter(
      src, n, digitBits, [&](size_t i) { return srcKeys[i] >> shift & mask; },
      [&](size_t at, size_t i, const Photon& p) {
        dst[at] = p;
        if (dstKeys) dstKeys[at] = srcKeys[i];
      });
}

// The second digit, bucket by bucket: each first-digit bucket is sorted stably by
// (key & mask) through a per-thread buffer (a bucket is small enough to stay mostly
// in cache) instead of a second streaming pass into a second full-size array.
template <class Photon>
void sortBuckets(Photon* photons, const uint32_t* keys, const std::vector<size_t>& starts, int digitBits) {
  const size_t buckets = size_t(1) << digitBits, mask = buckets - 1;
  struct Scratch {
    PhotonArray<Photon> buffer;
    std::vector<uint32_t> head;
  };
  size_t largest = 0;
  for (size_t b = 0; b + 1 < starts.size(); ++b) largest = std::max(largest, starts[b + 1] - starts[b]);
  // Each thread's buffer is sized once, to the largest bucket, on its first bucket.
  tbb::enumerable_thread_specific<Scratch> scratch([&] { return Scratch{PhotonArray<Photon>(largest), {}}; });
  tbb::parallel_for(size_t(0), starts.size() - 1, [&](size_t b) {
    const size_t begin = starts[b], end = starts[b + 1];
    if (end - begin < 2) return;
    Scratch& local = scratch.local();
    PhotonArray<Photon>& buffer = local.buffer;
    std::vector<uint32_t>& head = local.head;
    head.assign(buckets + 1, 0);
    for (size_t i = begin; i < end; ++i) ++head[(keys[i] & mask) + 1];
    for (size_t d = 1; d <= buckets; ++d) head[d] += head[d - 1];
    for (size_t i = begin; i < end; ++i) buffer[head[keys[i] & mask]++] = photons[i];
    std::copy(buffer.begin(), buffer.begin() + (end - begin), photons + begin);
  });
}
}  // namespace

// Fixed ranges of the sequence, whatever its batches: the work splits the same way
// for one batch (a prefix cut, a copy) as for thousands.
constexpr size_t kRange = size_t(1) << 14;

template <class Photon>
Bounds computeBounds(const PhotonBatches<Photon>& photons) {
  return tbb::parallel_reduce(
      tbb::blocked_range<size_t>(0, photons.size(), kRange), Bounds{},
      [&](const tbb::blocked_range<size_t>& r, Bounds b) {
        photons.forRange(r.begin(), r.end(), [&](size_t, const Photon& p) { b.extend(p.position); });
        return b;
      },
      [](Bounds a, const Bounds& b) {
        a.extend(b);
        return a;
      });
}

template <class Photon>
StorageKeys storageKeys(const PhotonBatches<Photon>& photons, bool byGroup, bool spatial, const Bounds& bounds) {
  const size_t n = photons.size();
  const uint32_t numGroups = !byGroup ? 1u : tbb::parallel_reduce(
      tbb::blocked_range<size_t>(0, n, kRange), 1u,
      [&](const tbb::blocked_range<size_t>& r, uint32_t most) {
        photons.forRange(r.begin(), r.end(),
                         [&](size_t, const Photon& p) { most = std::max(most, storageGroup(p) + 1); });
        return most;
      },
      [](uint32_t a, uint32_t b) { return std::max(a, b); });
  // Cells of 1/64 of the box per axis (fewer with many groups) give compact,
  // balanced parts and a cache-friendly build; the tree orders the rest.
  int bitsPerAxis = spatial ? 6 : 0;
  while (bitsPerAxis > 0 && (uint64_t(numGroups) << (3 * bitsPerAxis)) > (uint64_t(1) << 22)) --bitsPerAxis;
  const int cellBits = 3 * bitsPerAxis;
  int groupBits = 0;
  while ((uint32_t(1) << groupBits) < numGroups) ++groupBits;
  StorageKeys out;
  out.bits = cellBits + groupBits;
  out.keys.resize(n);
  tbb::parallel_for(tbb::blocked_range<size_t>(0, n, kRange), [&](const auto& r) {
    photons.forRange(r.begin(), r.end(), [&](size_t i, const Photon& p) {
      const uint32_t cell = cellBits ? coarseCell(p.position, bounds, bitsPerAxis) : 0u;
      out.keys[i] = (byGroup ? storageGroup(p) : 0u) << cellBits | cell;
    });
  });
  return out;
}

template <class Photon>
PhotonArray<Photon> sortByKey(PhotonBatches<Photon>&& photons, StorageKeys&& keys) {
  const size_t n = photons.size();
  if (n < 2 || keys.bits == 0) return std::move(photons).takeArray();
  const int passes = (keys.bits + kMaxRadixDigitBits - 1) / kMaxRadixDigitBits;
  const int digitBits = (keys.bits + passes - 1) / passes;
  // storageKeys keeps keys within 22 bits: at most two passes of <= 11 bits each.
  PhotonArray<Photon> sorted(n);
  if (passes == 1) {
    scatterPass(photons, keys.keys.data(), sorted.data(), nullptr, n, 0, digitBits);
    photons = PhotonBatches<Photon>();  // the emitters' blocks are read: free them now
    return sorted;
  }
  // Two digits: the high one streams out of the batches, the low one is sorted
  // within each high bucket (same order as two LSD passes: by key, then sequence).
  const int lowBits = digitBits, highBits = keys.bits - digitBits;
  PhotonArray<uint32_t> moved(n);  // the keys travel along to the second digit
  const std::vector<size_t> starts =
      scatterPass(photons, keys.keys.data(), sorted.data(), moved.data(), n, lowBits, highBits);
  photons = PhotonBatches<Photon>();  // the emitters' blocks are read: free them now
  keys.keys = PhotonArray<uint32_t>();
  sortBuckets(sorted.data(), moved.data(), starts, lowBits);
  return sorted;
}

#define PENUMBRA_MORTON_FOR(Photon)                                                                  \
  template Bounds computeBounds(const PhotonBatches<Photon>&);                                       \
  template StorageKeys storageKeys(const PhotonBatches<Photon>&, bool, bool, const Bounds&);        \
  template PhotonArray<Photon> sortByKey(PhotonBatches<Photon>&&, StorageKeys&&);
PENUMBRA_MORTON_FOR(ShadowPhoton)
PENUMBRA_MORTON_FOR(IndirectPhoton)
#undef PENUMBRA_MORTON_FOR

}  // namespace penumbra
