// What building the lookup cache knows of its photons, shared by its steps: every
// photon's cell key and source, sorted, where each record's photons start and which
// way they face, and per record and light stratum how the photons arrived.
#pragma once
#include "core/math.h"
#include "core/photon.h"
#include <cstddef>
#include <cstdint>
#include <vector>

namespace penumbra {

// One photon's key and where it came from: source 0 is the indirect map, 1 + l light l.
struct CacheEntry {
  uint64_t key;
  uint32_t index;
  uint32_t source;
};

// Sorts entries by key, ties in their given order: made in (source, index) order, each
// record's photons come out in that order. A radix sort over the bits the keys use.
void sortCacheEntries(PhotonArray<CacheEntry>& entries);

// One cell's votes for one stratum of a light, saturating at 255.
struct CellCounts {
  uint8_t direct = 0, opaque = 0, glass = 0;
};

// A key's cell and normal bucket (LookupCache::keyOf's layout: 20 bits an axis).
struct CellKey {
  int64_t x, y, z;
  unsigned bucket;
};
inline CellKey decodeCellKey(uint64_t key) {
  return {int64_t(key >> 44), int64_t(key >> 24 & 0xFFFFF), int64_t(key >> 4 & 0xFFFFF), unsigned(key & 15)};
}

struct CacheCells {
  PhotonArray<CacheEntry> entries;  // sorted by key
  std::vector<uint32_t> starts;     // record r's entries: [starts[r], starts[r + 1])
  std::vector<uint64_t> keys;       // record r's key
  std::vector<Vec3> normals;        // record r's photons' mean normal
  std::vector<CellCounts> counts;   // per record, numStrata of them
  size_t numStrata = 0;             // over all lights (LookupCache::strata_)
};

}  // namespace penumbra
