// The KD-tree over a photon array (nanoflann behind a small facade, so only
// kd_tree.cpp compiles nanoflann) and the per-thread scratch its queries fill.
#pragma once
#include "core/math.h"
#include "core/photon.h"
#include "core/progress.h"
#include <cstddef>
#include <cstdint>
#include <memory>
#include <vector>

namespace penumbra {

// Per-thread reusable query buffers: sized on first use, then every query reuses
// them, so steady-state queries never allocate. One per thread, never shared; one
// scratch may serve any number of trees (lights, maps) in any order.
//
// Besides the output arrays it keeps, per tree, search hints: recent queries'
// positions p_i and k-th-neighbour distances r_i. A query starts with a search
// bounded by a ball around it of radius min(r_i + |p - p_i|, 1.2 r_i) from the nearest
// recent query (the first term provably holds >= k photons), so the KD-tree prunes
// from the first node instead of widening from the nearest leaf; a ball that held
// fewer than k photons is searched again, larger. Hints change only the speed, never
// the answer: results are always exactly the k smallest (dist2, index) pairs, so
// they do not depend on query order, hint state or thread count. (Hints are keyed by
// the tree's address: a stale hint from a destroyed tree only costs speed.)
struct GatherScratch {
  std::vector<uint32_t> indices;  // into the map's photon array; nearest first (see knn)
  std::vector<float> dist2;       // squared distances, in the same order
  void reserve(size_t k) {
    if (indices.size() < k) {
      indices.resize(k);
      dist2.resize(k);
    }
  }

  // ---- search hints (performance only) ----
  bool useHints = true;            // false: every query is a plain bounded kNN
  float forcedHintRadius = -1.0f;  // tests: >= 0 replaces the hint by this radius
  uint64_t hintedQueries = 0;      // queries that started from a hint
  uint64_t hintReruns = 0;         // ... whose hint ball held < k photons (searched again)
  // Per tree, the last few queries' positions and k-th-neighbour distances: the
  // tracer interleaves several coherent streams (camera hits, reflection and
  // refraction hits), so a query takes its hint from the nearest recent one.
  static constexpr size_t kHintEntries = 4;
  struct Hint {
    const void* tree = nullptr;
    size_t k = 0;
    Vec3 p[kHintEntries];
    float r[kHintEntries] = {-1.0f, -1.0f, -1.0f, -1.0f};  // < 0: no usable hint
    unsigned next = 0;  // the entry to overwrite when no recent one is near
  };
  static constexpr size_t kHintSlots = 8;
  Hint hints[kHintSlots];
  size_t nextHintSlot = 0;
  void clearHints() {
    for (Hint& h : hints) h = Hint{};
  }
  // The slot of (tree, k) (claims the oldest-claimed slot on a miss).
  Hint& hintFor(const void* tree, size_t k) {
    for (Hint& h : hints)
      if (h.tree == tree && h.k == k) return h;
    Hint& h = hints[nextHintSlot];
    nextHintSlot = (nextHintSlot + 1) % kHintSlots;
    claim(h, tree, k);
    return h;
  }
  static void claim(Hint& h, const void* tree, size_t k) {
    h = Hint{};
    h.tree = tree;
    h.k = k;
  }
  std::vector<uint64_t> keys;  // candidate buffer of the selection: (dist2 bits << 32) | index
  std::vector<uint32_t> buckets;  // sort scratch
};

// How a photon map is built. The defaults are the faster choices in bench_gather:
// Morton order speeds both build and queries, and leaves of 48 photons build faster
// than leaves of 24 at about the same k = 50 query cost.
struct MapBuildOptions {
  bool mortonSort = true;
  size_t leafSize = 48;
  // Shadow map, in Morton order: false leaves out its KD-trees, which precomputed
  // lookups never read, until ShadowPhotonMap::buildTrees (photons stay in order).
  bool shadowTrees = true;
  // Counts 2 per photon: one when the map's photons are ordered, one as the part
  // holding it is built (one atomic add per map and per part); null: none.
  ProgressCounter* progress = nullptr;
};

// A KD-tree over the positions of a photon array it does not own (but reorders at
// build). The array must outlive the tree and keep its buffer (moving a std::vector
// keeps it; copying or resizing does not).
template <class Photon>
class PhotonKdTree {
 public:
  PhotonKdTree();
  ~PhotonKdTree();
  PhotonKdTree(PhotonKdTree&&) noexcept;
  PhotonKdTree& operator=(PhotonKdTree&&) noexcept;

  // Builds over `photons`, then permutes the array into the tree's leaf order (so a
  // leaf's photons are contiguous and the index indirection reads sequentially).
  // Any index into the array is only meaningful after this returns.
  // The tree is a set of parts (contiguous ranges built side by side), which must be
  // spatially compact: either the input is already in spatial (Morton) order, or
  // `split` first arranges it in place by median splits (slower: the build then reads
  // photons in a random order).
  // Each part built adds its photon count to `progress` (if any).
  void build(PhotonArray<Photon>& photons, size_t leafSize, bool split = false,
             ProgressCounter* progress = nullptr) {
    build(photons.data(), photons.size(), leafSize, split, progress);
  }
  // The same over photons[0..count) of an array the caller keeps in place. With
  // `reorder` false the photons keep their order (already spatial, so `split` must be
  // false) and the tree reads them through its index permutation.
  void build(Photon* photons, size_t count, size_t leafSize, bool split = false,
             ProgressCounter* progress = nullptr, bool reorder = true);
  // The k nearest photons strictly closer than maxRadius (0 = unlimited) into
  // scratch.indices/dist2; returns how many (min(k, photons in range)). "Nearest" is
  // by (dist2, index): ties at the k-th distance keep the lower indices, so the
  // answer is unique. If sorted, ascending (dist2, index); otherwise in no
  // particular order (enough for order-independent consumers such as the gate vote).
  size_t knn(const Vec3& p, size_t k, float maxRadius, GatherScratch& scratch,
             bool sorted = true) const;
  // Every photon strictly closer than radius into scratch.indices/dist2, in no
  // particular order; returns how many. The buffers grow as needed and are kept.
  size_t within(const Vec3& p, float radius, GatherScratch& scratch) const;
  // KD-tree nodes (pool, including its slack) + the index permutation; not the photons.
  size_t memoryBytes() const;

 private:
  struct Impl;
  std::unique_ptr<Impl> impl_;
};

extern template class PhotonKdTree<ShadowPhoton>;
extern template class PhotonKdTree<IndirectPhoton>;

}  // namespace penumbra
