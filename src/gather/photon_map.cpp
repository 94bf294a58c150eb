// Building and querying the shadow and indirect photon maps.
#include "gather/photon_map.h"
#include "gather/morton.h"
#include "core/error.h"
#include <fmt/format.h>
#include <algorithm>
#include <cassert>
#include <limits>
#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>

namespace penumbra {

namespace {
// Indices into a map are 32-bit (KD-tree, lookup cache): refuse what they cannot name.
void checkIndexable(size_t count, const char* which) {
  if (count > std::numeric_limits<uint32_t>::max()) {
    throw InputError(fmt::format("photons: {} stored {} photons exceed the 2^32 one map can index; "
                                 "emit fewer", count, which));
  }
}
}  // namespace

// ---- ShadowPhotonMap ------------------------------------------------------------

void ShadowPhotonMap::build(PhotonBatches<ShadowPhoton> photons, size_t numLights,
                            const MapBuildOptions& options) {
  lights_.clear();
  lights_.resize(numLights);
  size_ = 0;
  checkIndexable(photons.size(), "shadow");
  const size_t given = photons.size();
  photons_.clear();
  if (given > 0 && numLights > 0) {
    // One sort does both jobs: the light index is the primary key, so each light's
    // photons come out contiguous and, within it, spatially ordered.
    Bounds bounds = options.mortonSort ? computeBounds(photons) : Bounds{};
    StorageKeys keys = storageKeys(photons, /*byGroup=*/true, options.mortonSort, bounds);
    photons_ = sortByKey(std::move(photons), std::move(keys));
    size_t begin = 0;
    for (size_t light = 0; light < numLights; ++light) {
      size_t end = begin;
      while (end < photons_.size() && photons_[end].light == light) ++end;
      lights_[light].begin = begin;
      lights_[light].count = end - begin;
      begin = end;
    }
    // Sorted by light: whatever is left has light >= numLights and is dropped.
    size_ = begin;
    photons_.resize(size_);
  }
  // Ordered, and the dropped photons' share of the parts: the trees count the rest.
  progressAdd(options.progress, given + (given - size_));
  leafSize_ = options.leafSize;
  treesBuilt_ = false;
  if (!options.shadowTrees && options.mortonSort) {
    progressAdd(options.progress, size_);  // the trees' share, not spent
    return;
  }
  // Lights are independent trees; each also builds its parts side by side.
  tbb::parallel_for(size_t(0), numLights, [&](size_t light) {
    PerLight& l = lights_[light];
    l.tree.build(photons_.data() + l.begin, l.count, options.leafSize, !options.mortonSort, options.progress);
  });
  treesBuilt_ = true;
}

void ShadowPhotonMap::buildTrees(ProgressCounter* progress) {
  if (treesBuilt_) return;
  tbb::parallel_for(size_t(0), lights_.size(), [&](size_t light) {
    PerLight& l = lights_[light];
    l.tree.build(photons_.data() + l.begin, l.count, leafSize_, /*split=*/false, progress, /*reorder=*/false);
  });
  treesBuilt_ = true;
}

bool ShadowPhotonMap::hasPhotons(uint32_t light) const {
  return light < lights_.size() && lights_[light].count > 0;
}

size_t ShadowPhotonMap::knn(const Vec3& p, uint32_t light, size_t k, float maxRadius,
                            GatherScratch& scratch) const {
  if (light >= lights_.size()) return 0;
  assert(treesBuilt_ && "ShadowPhotonMap::buildTrees first");
  return lights_[light].tree.knn(p, k, maxRadius, scratch);
}

GateVerdict ShadowPhotonMap::classify(const Vec3& p, const Vec3& n, uint32_t light,
                                      const GateParams& params, GatherScratch& scratch, bool backSide) const {
  if (params.k <= 0) return GateVerdict::Mixed;
  if (light >= lights_.size()) return GateVerdict::Mixed;
  assert(treesBuilt_ && "ShadowPhotonMap::buildTrees first");
  // The vote only counts kinds, so the k nearest need not be sorted.
  size_t found = lights_[light].tree.knn(p, static_cast<size_t>(params.k), params.maxRadius,
                                         scratch, /*sorted=*/false);
  if (found == 0) return GateVerdict::Mixed;
  return voteGate(photons_.data() + lights_[light].begin, scratch.indices.data(), found, n, params, backSide);
}

size_t ShadowPhotonMap::size() const { return size_; }

size_t ShadowPhotonMap::memoryBytes() const {
  size_t bytes = lights_.capacity() * sizeof(PerLight) + photons_.capacity() * sizeof(ShadowPhoton);
  for (const PerLight& l : lights_) bytes += l.tree.memoryBytes();
  return bytes;
}

PhotonRange<ShadowPhoton> ShadowPhotonMap::photons(uint32_t light) const {
  if (light >= lights_.size()) return {};
  return {photons_.data() + lights_[light].begin, lights_[light].count};
}

// ---- IndirectPhotonMap ----------------------------------------------------------

void IndirectPhotonMap::build(PhotonBatches<IndirectPhoton> photons,
                              const MapBuildOptions& options) {
  checkIndexable(photons.size(), "indirect");
  if (options.mortonSort && !photons.empty()) {
    StorageKeys keys = storageKeys(photons, /*byGroup=*/false, true, computeBounds(photons));
    photons_ = sortByKey(std::move(photons), std::move(keys));
  } else {
    photons_ = std::move(photons).takeArray();
  }
  progressAdd(options.progress, photons_.size());
  tree_.build(photons_, options.leafSize, !options.mortonSort, options.progress);
  topExponent_ = 0;
  for (const IndirectPhoton& ph : photons_) topExponent_ = std::max(topExponent_, ph.power.bits >> 24);
}

size_t IndirectPhotonMap::knn(const Vec3& p, size_t k, float maxRadius, GatherScratch& scratch,
                              bool sorted) const {
  return tree_.knn(p, k, maxRadius, scratch, sorted);
}

IndirectPhotonMap::Estimate IndirectPhotonMap::classic(const Vec3& p, const Vec3& n, int k,
                                                       float maxRadius, GatherScratch& s,
                                                       float minNormalCos) const {
  if (k <= 0) return {};
  // Sorted although the estimate only sums and takes a maximum: the selection's own
  // order depends on the search hints (per thread), and a float sum on its order.
  size_t found = tree_.knn(p, static_cast<size_t>(k), maxRadius, s);
  return classicEstimate(photons_.data(), s, found, n, minNormalCos);
}

IndirectPhotonMap::Estimate IndirectPhotonMap::density(const Vec3& p, const Vec3& n, int k,
                                                       float maxRadius, GatherScratch& s,
                                                       float minNormalCos) const {
  if (k <= 0) return {};
  size_t found = tree_.knn(p, static_cast<size_t>(k), maxRadius, s);  // sorted: see classic()
  return densityEstimate(photons_.data(), s, found, n, minNormalCos);
}

size_t IndirectPhotonMap::memoryBytes() const {
  return photons_.capacity() * sizeof(IndirectPhoton) + tree_.memoryBytes();
}

}  // namespace penumbra
