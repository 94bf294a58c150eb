// The distance from a few probe points to their k-th nearest photon, exactly (the
// squared distances a KD-tree's k-nearest search computes), without a tree: a cell
// size wants 256 such probes, and one pass binning the photons into a grid costs
// far less than the tree over all of them that nothing else may read.
#pragma once
#include "core/math.h"
#include <cstddef>
#include <vector>

namespace penumbra {

// One distance per probe: to its k-th nearest of positions[0..count) (to the farthest
// when count < k; 0 when count or k is 0). Each squared distance is summed in axis
// order, as nanoflann's L2 metric does, so the results equal a tree's to the bit.
std::vector<float> kthNearestDistances(const Vec3* positions, size_t count, size_t stride,
                                       const std::vector<Vec3>& probes, size_t k);

// The same over an array of photons (anything with a `position`).
template <class Photon>
std::vector<float> kthNearestDistances(const Photon* photons, size_t count, const std::vector<Vec3>& probes,
                                       size_t k) {
  if (count == 0) return std::vector<float>(probes.size(), 0.0f);
  static_assert(sizeof(Photon) % sizeof(float) == 0, "positions are read with a stride in floats");
  return kthNearestDistances(&photons[0].position, count, sizeof(Photon), probes, k);
}

}  // namespace penumbra
