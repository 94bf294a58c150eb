// Spatial ordering of photon arrays: bounding boxes, 63-bit Morton codes and the
// deterministic (group, cell, index) radix sort the photon maps store their photons in.
#pragma once
#include "core/math.h"
#include "core/photon.h"
#include "core/photon_batches.h"
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

// The group photons are stored by: a shadow photon's light; one group otherwise.
inline uint32_t storageGroup(const ShadowPhoton& p) { return p.light; }
inline uint32_t storageGroup(const IndirectPhoton&) { return 0; }

// Bounding box of all positions (parallel over the batches).
template <class Photon>
Bounds computeBounds(const PhotonBatches<Photon>& photons);

// The key photons are stored by: the group (storageGroup, if byGroup) in the high
// bits, then, if spatial, a coarse Morton cell over `bounds` (the KD-tree build orders
// finely). `bits` is the key's width.
struct StorageKeys {
  PhotonArray<uint32_t> keys;  // uninitialised until written: one per photon
  int bits = 0;
};
template <class Photon>
StorageKeys storageKeys(const PhotonBatches<Photon>& photons, bool byGroup, bool spatial, const Bounds& bounds);

// The photons sorted by key, ties in their sequence order, so the order is that of a
// serial stable sort for any thread count. The key's high digit (<= 11 bits) streams
// straight out of the batches the emitters left (no merged copy; they are freed
// after) into at most 2048 buckets over fixed chunks; a low digit, if any, is then
// sorted inside each bucket through a per-thread buffer, not a second full-size
// array. Consumes the keys.
template <class Photon>
PhotonArray<Photon> sortByKey(PhotonBatches<Photon>&& photons, StorageKeys&& keys);

}  // namespace penumbra
