// Precomputed photon lookups (Christensen 1999, "Faster photon map global
// illumination"): the gate's verdict for every light and the indirect estimate,
// computed once per cell of a spatial hash, then read with one query per shading point.
#pragma once
#include "core/math.h"
#include "core/progress.h"
#include "core/rng.h"
#include "gather/photon_map.h"
#include "gather/stratum_split.h"
#include <atomic>
#include <cstddef>
#include <cstdint>
#include <memory>
#include <vector>

namespace penumbra {

struct CacheCells;  // lookup_cache_cells.h: what building a cache knows of its photons

// Which indirect estimate the cache holds (the exact estimators of indirect_estimate.h
// and radiance_estimate.h, evaluated at the cell's photons' centroid; Irradiance at
// the cell's centre on their plane, lookup_cache.cpp's centredSite).
enum class CachedIndirect : uint8_t {
  None,
  Classic,     // the report's cone-weighted average (classic model)
  Density,     // Jensen's cone-filtered irradiance (classic model, density estimator)
  Irradiance,  // the Epanechnikov-weighted flux density: photonRadiance over rho/pi
};

struct LookupCacheParams {
  float cellSize = 0.0f;  // world units (> 0); see cacheCellSize()
  CachedIndirect indirect = CachedIndirect::None;
  int k = 50;              // photons per indirect estimate
  float maxRadius = 0.0f;  // classic/density: bound of the k-nearest gather (0 = none)
  float radius = 0.0f;     // irradiance: PhotonGather's bound (k = 0: a fixed radius)
  bool gate = false;       // precompute shadow-gate verdicts
  GateParams gateParams;
  // Once the cells are known, expects one unit per cell and step (summary, vote,
  // estimate) and adds each chunk's cells when done; null: none.
  ProgressCounter* progress = nullptr;
};

// Whether a cache built with `a` answers for `b` (every parameter but the progress).
inline bool sameLookup(const LookupCacheParams& a, const LookupCacheParams& b) {
  return a.cellSize == b.cellSize && a.indirect == b.indirect && a.k == b.k && a.maxRadius == b.maxRadius &&
         a.radius == b.radius && a.gate == b.gate && a.gateParams == b.gateParams;
}

// The cell size: `scale` times the median distance to the k-th nearest photon of
// `map` (at most 256 probes), but never so small that the cells outnumber the map's
// photons / kMinPhotonsPerCell: a cell must cost less than the gathers it replaces.
// A cache of gate verdicts alone costs a linear count, not gathers, so its cells
// may be finer: kMinPhotonsPerGateCell.
constexpr float kMinPhotonsPerCell = 16.0f;
constexpr float kMinPhotonsPerGateCell = 4.0f;
float cacheCellSize(const IndirectPhotonMap* indirect, int k, const ShadowPhotonMap* shadow,
                    int kShadow, float scale);
// The same from a known gather radius r holding about k photons.
float cacheCellSize(float r, int k, float scale, float minPhotonsPerCell = kMinPhotonsPerCell);
// How many photons such a cell holds where they lie on a plane, k h^2 / (pi r^2):
// what a cache's record count follows (the resource estimate).
float photonsPerCacheCell(int k, float scale, float minPhotonsPerCell = kMinPhotonsPerCell);

class LookupCache {
 public:
  // A key's bucket is 4 bits: the normal's bucket, plus kBackSideBucket for the shadow
  // photons that met their surface from behind (a closed object's far wall, seen from
  // inside): a thin wall's exit hits, a cell or less behind its front face and turned
  // the same way, stay out of the front face's vote.
  static constexpr unsigned kBackSideBucket = 8;
  // A key's bucket from the normal's and the side; the normal's axis back from a key's.
  static unsigned sidedBucket(unsigned normalBucket, bool backSide) {
    return normalBucket | (backSide ? kBackSideBucket : 0u);
  }
  static unsigned bucketAxis(unsigned bucket) { return (bucket & ~kBackSideBucket) / 2; }
  // Cells are keyed by position and the dominant axis of the surface normal (six
  // buckets), so a thin wall's two sides and a corner's two faces never share a cell,
  // and a shadow photon's also by the side it met (kBackSideBucket).
  // Either map may be null or empty; a cell exists where either map has photons.
  void build(const ShadowPhotonMap* shadow, const IndirectPhotonMap* indirect,
             const LookupCacheParams& params);
  bool empty() const { return records_ == 0; }

  // The answer at one shading point: the indirect estimate blended bilinearly from
  // the up to 4 cells around p (across the surface, in p's layer along the normal's
  // axis) that share n's bucket, and the gate verdicts of p's own cell. Where the
  // photons are sparse some cells hold none: p's verdicts are then those of the
  // nearest of the 8 cells around it in its layer (whose vote spans p's cell too),
  // and nullptr only when none of them has a record (the caller casts shadow rays).
  struct Answer {
    Color indirect{0.0f};
    bool hasIndirect = false;           // false: no cell near p; use the exact estimate
    // One GateVerdict per light, then one per stratum of each light (stratumVerdict).
    const uint8_t* verdicts = nullptr;
  };
  // backSide: p was met from behind its surface's winding (SurfaceRecord::frontFace
  // false); its verdicts come from the photons that met the surface from behind too.
  Answer find(const Vec3& p, const Vec3& n, bool backSide = false) const;

  // Where find() has no cell near p (a surface no photon reached in that orientation:
  // the inside of a glass ball, a wall's far side), the estimate of p's own (cell,
  // bucket): the cache's estimator at the cell's centre, with the bucket's axis as the
  // normal, computed on first use and kept. A pure function of the key, so every
  // thread reads the same value whoever computed it (images stay identical for any
  // thread count); `map` must be the map the cache was built from.
  Color lazyIndirect(const IndirectPhotonMap& map, const Vec3& p, const Vec3& n, GatherScratch& s) const;
  Vec3 cellCentreOf(const Vec3& p) const { return origin_ + (glm::floor((p - origin_) * invCell_) + Vec3(0.5f)) * cell_; }
  size_t lazyCells() const { return lazy_ ? lazy_->count.load(std::memory_order_relaxed) : 0; }

  bool hasGate() const { return numLights_ > 0; }
  // How many strata light l's photons name (core/light_strata.h), and the verdict
  // of one at p, from the row of p's cell (Answer::verdicts): only where the light's
  // own verdict is mixed can they differ from it. A stratum whose photons around the
  // cell disagree answers by p's side of the line between them (stratum_split.h).
  int strataOf(uint32_t light) const { return light < numLights_ ? strata_[light] : 1; }
  GateVerdict stratumVerdict(const uint8_t* row, uint32_t light, int stratum, const Vec3& p) const {
    const size_t column = numLights_ + strataStart_[light] + static_cast<size_t>(stratum);
    return row[column] == kSplit ? splitAt(row, column).at(p) : static_cast<GateVerdict>(row[column]);
  }
  CachedIndirect indirectKind() const { return kind_; }
  size_t records() const { return records_; }
  size_t splitLines() const { return splits_.size(); }
  size_t numLights() const { return numLights_; }
  float cellSize() const { return cell_; }
  size_t memoryBytes() const;
  // What a cache of `records` records costs: per record its hash slots (2 to 4), its
  // row of verdicts (`verdictColumns`: a light's and each stratum's, 0 without the
  // gate) with `splitsPerRecord` split lines; with an indirect estimate, the lazy table.
  static double estimateBytes(double records, size_t verdictColumns, double splitsPerRecord, bool indirect);

 private:
  // A probe touches one slot: the indirect value lives in it, not behind the index.
  struct Slot {
    uint64_t key = kEmpty;
    Color indirect{0.0f};
    uint32_t record = 0;
  };
  static constexpr uint64_t kEmpty = ~uint64_t(0);
  // A stratum's byte in a row when its verdict is its split's (after the GateVerdicts).
  static constexpr uint8_t kSplit = static_cast<uint8_t>(GateVerdict::Mixed) + 1;
  const StratumSplit& splitAt(const uint8_t* row, size_t column) const;
  void voteGate(const CacheCells& cells, const ShadowPhotonMap& shadow, const LookupCacheParams& params);
  // The dominant axis of n and its sign: 0..5 (axis = bucket / 2, negative if odd).
  static unsigned bucketOf(const Vec3& n) {
    const Vec3 a = glm::abs(n);
    const unsigned axis = a.x >= a.y && a.x >= a.z ? 0u : (a.y >= a.z ? 1u : 2u);
    return 2u * axis + (n[axis] < 0.0f ? 1u : 0u);
  }
  // A full 64-bit mix: keys of one layer differ only in x and y, whose bits a
  // multiplicative hash's middle bits do not see (rows of cells collided into long runs).
  static size_t slotHash(uint64_t key) { return static_cast<size_t>(mix64(key)); }
  uint64_t keyOf(int64_t x, int64_t y, int64_t z, unsigned bucket) const;
  uint64_t keyAt(const Vec3& p, unsigned bucket) const;
  const Slot* slotOf(uint64_t key) const;  // nullptr: none
  int32_t recordOf(uint64_t key) const { const Slot* s = slotOf(key); return s ? int32_t(s->record) : -1; }
  // The verdict row of the record nearest p among the 8 cells around `own` across
  // the surface (axis: the bucket's), or nullptr; `cellOf` is p in cell units.
  const uint8_t* verdictsAround(const int64_t* own, const Vec3& cellOf, unsigned bucket) const;
  void insertKeys(const std::vector<uint64_t>& sortedKeys);

  // lazyIndirect's cells: open addressing, claimed by CAS on the key; `ready` publishes
  // the value. A full table (or a long probe) computes without keeping.
  struct LazySlot {
    std::atomic<uint64_t> key{kEmpty};
    std::atomic<uint32_t> ready{0};
    Color value{0.0f};
  };
  struct LazyTable {
    std::unique_ptr<LazySlot[]> slots;
    size_t mask = 0;
    std::atomic<size_t> count{0};
  };
  void makeLazyTable();
  Color estimateAt(const IndirectPhotonMap& map, const Vec3& p, const Vec3& n, GatherScratch& s) const;
  std::unique_ptr<LazyTable> lazy_;  // behind a pointer: the cache stays movable
  int k_ = 50;
  float maxRadius_ = 0.0f, radius_ = 0.0f;

  Vec3 origin_{0.0f};
  float cell_ = 1.0f, invCell_ = 1.0f;
  size_t records_ = 0, numLights_ = 0;
  CachedIndirect kind_ = CachedIndirect::None;
  std::vector<Slot> slots_;        // open addressing, power-of-two size, linear probing
  std::vector<uint8_t> verdicts_;  // per record: rowWidth_ GateVerdicts (lights, then strata)
  std::vector<uint8_t> strata_;       // per light: its strata
  std::vector<uint32_t> strataStart_;  // per light: its first stratum's place after the lights
  std::vector<StratumSplit> splits_;   // the split strata, by record, then place in the row
  std::vector<uint32_t> splitStart_;   // per record and one past: its first split
  size_t rowWidth_ = 0;
};

}  // namespace penumbra
