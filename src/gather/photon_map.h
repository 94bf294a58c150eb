// The two photon maps the tracer queries: the shadow map (one KD-tree per light,
// feeding the shadow gate) and the indirect map (feeding the indirect estimators).
#pragma once
#include "core/photon.h"
#include "core/photon_batches.h"
#include "gather/indirect_estimate.h"
#include "gather/kd_tree.h"
#include "gather/photon_map_for.h"
#include "gather/shadow_gate.h"
#include <cstddef>
#include <cstdint>
#include <vector>

namespace penumbra {

// A read-only view of a contiguous run of photons (C++17 has no std::span).
template <class Photon>
struct PhotonRange {
  const Photon* first = nullptr;
  size_t count = 0;
  const Photon* data() const { return first; }
  size_t size() const { return count; }
  bool empty() const { return count == 0; }
  const Photon& operator[](size_t i) const { return first[i]; }
  const Photon* begin() const { return first; }
  const Photon* end() const { return first + count; }
};

class ShadowPhotonMap {
 public:
  // Takes ownership and orders the photons by light, then spatially (coarse Morton
  // cells, if options.mortonSort: a radix sort straight out of the batches), then builds
  // one KD-tree per light over its range, which leaves each range in its tree's leaf
  // order (in place). Photons whose light is >= numLights are dropped. With
  // options.shadowTrees false (and Morton order) the trees wait for buildTrees.
  void build(PhotonBatches<ShadowPhoton> photons, size_t numLights,
             const MapBuildOptions& options = {});
  // The KD-trees that classify and knn read, if build left them out: built over the
  // photons in their Morton order, which they keep, so whatever was computed from the
  // photons before (a lookup cache, its cell size) is computed the same after. Not
  // thread-safe: call it before the threads that query.
  void buildTrees(ProgressCounter* progress = nullptr);
  bool hasTrees() const { return treesBuilt_; }
  bool hasPhotons(uint32_t light) const;
  // backSide: as voteGate's (the point met from behind its surface's winding).
  GateVerdict classify(const Vec3& p, const Vec3& n, uint32_t light, const GateParams& params,
                       GatherScratch& scratch, bool backSide = false) const;
  // Raw kNN for tests and benchmarks: up to k photons of `light` strictly closer than
  // maxRadius (0 = unlimited), nearest first, into scratch.indices (into photons(light))
  // and scratch.dist2 (squared distances). Returns how many.
  size_t knn(const Vec3& p, uint32_t light, size_t k, float maxRadius,
             GatherScratch& scratch) const;
  size_t size() const;         // photons stored
  size_t memoryBytes() const;  // photon arrays + KD-tree nodes/indices
  size_t numLights() const { return lights_.size(); }
  PhotonRange<ShadowPhoton> photons(uint32_t light) const;

 private:
  struct PerLight {
    size_t begin = 0, count = 0;  // the light's range of photons_
    PhotonKdTree<ShadowPhoton> tree;
  };
  PhotonArray<ShadowPhoton> photons_;  // every light's, by light
  std::vector<PerLight> lights_;
  size_t size_ = 0;
  size_t leafSize_ = 48;
  bool treesBuilt_ = false;
};

class IndirectPhotonMap {
 public:
  using Estimate = IndirectEstimate;

  // Takes ownership; coarse Morton order (a radix sort out of the batches), then leaf
  // order in place.
  void build(PhotonBatches<IndirectPhoton> photons, const MapBuildOptions& options = {});
  bool empty() const { return photons_.empty(); }
  // Gather the k nearest photons (within maxRadius if > 0) and estimate; see
  // indirect_estimate.h for the formulas and the normal filter.
  Estimate classic(const Vec3& p, const Vec3& n, int k, float maxRadius, GatherScratch& s,
                   float minNormalCos = kIndirectMinNormalCos) const;
  Estimate density(const Vec3& p, const Vec3& n, int k, float maxRadius, GatherScratch& s,
                   float minNormalCos = kIndirectMinNormalCos) const;
  // Raw kNN, as ShadowPhotonMap::knn; indices into photons(). Sorted nearest first
  // unless `sorted` is false (then in no particular order, and cheaper).
  size_t knn(const Vec3& p, size_t k, float maxRadius, GatherScratch& scratch,
             bool sorted = true) const;
  // Every photon closer than radius, unordered; indices into photons().
  size_t within(const Vec3& p, float radius, GatherScratch& scratch) const {
    return tree_.within(p, radius, scratch);
  }
  size_t size() const { return photons_.size(); }
  size_t memoryBytes() const;
  const PhotonArray<IndirectPhoton>& photons() const { return photons_; }
  // The largest shared exponent byte among the photons' powers (0: all black), which
  // bounds every photon's power: the scale of order-independent fixed-point sums.
  uint32_t topPowerExponent() const { return topExponent_; }

 private:
  PhotonArray<IndirectPhoton> photons_;
  PhotonKdTree<IndirectPhoton> tree_;
  uint32_t topExponent_ = 0;
};

}  // namespace penumbra
