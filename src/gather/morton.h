// Spatial ordering of photon arrays: bounding boxes, 63-bit Morton codes and the
// deterministic (group, cell, index) radix sort the photon maps store their photons in.
#pragma once
#include "core/math.h"
#include "core/photon.h"
#include <cstddef>
#include <cstdint>
#include <vector>

namespace penumbra {

struct Bounds {
  Vec3 lo{kInf};
  Vec3 hi{-kInf};
  void extend(const Vec3& p) { lo = glm::min(lo, p); hi = glm::max(hi, p); }
  void extend(const Bounds& b) { lo = glm::min(lo, b.lo); hi = glm::max(hi, b.hi); }
  bool empty() const { return !(lo.x <= hi.x && lo.y <= hi.y && lo.z <= hi.z); }
};

// Spreads the low 21 bits of v so two zero bits separate each (bit i -> bit 3i).
uint64_t spreadBits21(uint32_t v);

// 63-bit Morton code of p quantised to 2^21 cells per axis over b. Degenerate axes
// (zero extent: a plane, a line, identical points) quantise to 0 instead of NaN.
uint64_t mortonCode63(const Vec3& p, const Bounds& b);

// A strided view of positions inside an array of photon records, so the ordering
// code serves every photon type without copying positions out.
struct PositionView {
  const unsigned char* base = nullptr;
  size_t stride = 0;
  size_t count = 0;
  const Vec3& operator[](size_t i) const {
    return *reinterpret_cast<const Vec3*>(base + i * stride);
  }
};
template <class Array>
PositionView positionsOf(const Array& photons) {
  using Photon = typename Array::value_type;
  return {reinterpret_cast<const unsigned char*>(photons.data()) +
              offsetof(Photon, position),
          sizeof(Photon), photons.size()};
}

// Bounding box of all positions (parallel reduction).
Bounds computeBounds(const PositionView& positions);

// The key photons are stored by: group (light index; pass nullptr for one group) in
// the high bits, then, if spatial, a coarse Morton cell over `bounds` (the KD-tree
// build orders finely). `bits` is the key's width.
struct StorageKeys {
  std::vector<uint32_t> keys;
  int bits = 0;
};
StorageKeys storageKeys(const PositionView& positions, const uint16_t* groups, size_t groupStride,
                        bool spatial, const Bounds& bounds);

// Sorts photons (and their keys) by key, ties in their original order: one or two
// scatter passes of a least-significant-digit radix sort over fixed chunks, so the
// order is that of a serial stable sort for any thread count. Streaming writes into
// at most 2048 buckets per pass instead of a gather at random: fig14's indirect map
// sorts in a fraction of the gather's time. Uses one second array while it runs.
template <class Photon>
void sortByKey(PhotonArray<Photon>& photons, StorageKeys& keys);

// Reorders a[0..n) so that a[i] becomes the old a[perm[i]], in place, by following
// the permutation's cycles; leaves perm as the identity.
template <class T>
void permuteInPlace(T* a, uint32_t* perm, size_t n) {
  for (size_t i = 0; i < n; ++i) {
    if (perm[i] == i) continue;
    T first = a[i];
    size_t j = i;
    for (;;) {
      const size_t k = perm[j];
      perm[j] = static_cast<uint32_t>(j);
      if (k == i) {
        a[j] = first;
        break;
      }
      a[j] = a[k];
      j = k;
    }
  }
}
}  // namespace penumbra
