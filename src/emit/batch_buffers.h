// Photon storage during emission: one vector per batch, merged in batch order, so
// the stored arrays do not depend on which thread ran which batch.
#pragma once
#include "core/photon.h"
#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>
#include <algorithm>
#include <cstdint>
#include <vector>

namespace penumbra {

// Each batch task fills only its own vector (disjoint writes, nothing shared); the
// merged array is allocated uninitialised (PhotonArray) so the parallel copy faults it in.
// Small per-batch vectors grow inside the cache; one large per-thread vector would
// copy everything it holds at every doubling and fault in fresh pages each time.
template <class Photon>
class BatchBuffers {
 public:
  explicit BatchBuffers(size_t batches) : batches_(batches) {}
  PhotonArray<Photon>& batch(size_t b) { return batches_[b]; }
  // Photons each batch stored, in batch order (before merge()).
  std::vector<size_t> sizes() const {
    std::vector<size_t> n(batches_.size());
    for (size_t i = 0; i < batches_.size(); ++i) n[i] = batches_[i].size();
    return n;
  }

  // All batches' photons in batch order; each batch is freed once copied.
  PhotonArray<Photon> merge() {
    std::vector<size_t> offset(batches_.size() + 1, 0);
    for (size_t i = 0; i < batches_.size(); ++i) offset[i + 1] = offset[i] + batches_[i].size();
    PhotonArray<Photon> out(offset.back());
    tbb::parallel_for(tbb::blocked_range<size_t>(0, batches_.size(), 8), [&](const auto& r) {
      for (size_t i = r.begin(); i != r.end(); ++i) {
        std::copy(batches_[i].begin(), batches_[i].end(), out.begin() + offset[i]);
        PhotonArray<Photon>().swap(batches_[i]);
      }
    });
    batches_.clear();
    return out;
  }

 private:
  std::vector<PhotonArray<Photon>> batches_;
};

}  // namespace penumbra
