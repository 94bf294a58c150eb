// The KD-tree over a photon array (nanoflann behind a small facade, so only
// kd_tree.cpp compiles nanoflann) and the per-thread scratch its queries fill.
#pragma once
#include "core/math.h"
#include "core/photon.h"
#include <cstddef>
#include <cstdint>
#include <memory>
#include <vector>

namespace penumbra {

// Per-thread reusable query buffers: sized to k on first use, then every query
// reuses them, so steady-state queries never allocate. One per thread, never shared.
struct GatherScratch {
  std::vector<uint32_t> indices;  // nearest first, into the map's (sorted) photon array
  std::vector<float> dist2;       // squared distances, ascending
  void reserve(size_t k) {
    if (indices.size() < k) {
      indices.resize(k);
      dist2.resize(k);
    }
  }
};

// How a photon map is built. The defaults are the measured-faster choices
// (bench_gather: Morton order speeds both build and queries; leaf size 24).
struct MapBuildOptions {
  bool mortonSort = true;
  size_t leafSize = 24;
};

// A KD-tree over the positions of a photon array it does not own. The array must
// outlive the tree and keep its buffer (moving a std::vector keeps it; copying or
// resizing does not).
template <class Photon>
class PhotonKdTree {
 public:
  PhotonKdTree();
  ~PhotonKdTree();
  PhotonKdTree(PhotonKdTree&&) noexcept;
  PhotonKdTree& operator=(PhotonKdTree&&) noexcept;

  void build(const std::vector<Photon>& photons, size_t leafSize);
  // Up to k nearest photons strictly closer than maxRadius (0 = unlimited), nearest
  // first, into scratch.indices/dist2; returns how many.
  size_t knn(const Vec3& p, size_t k, float maxRadius, GatherScratch& scratch) const;
  // KD-tree nodes (pool, including its slack) + the index permutation; not the photons.
  size_t memoryBytes() const;

 private:
  struct Impl;
  std::unique_ptr<Impl> impl_;
};

extern template class PhotonKdTree<ShadowPhoton>;
extern template class PhotonKdTree<IndirectPhoton>;

}  // namespace penumbra
