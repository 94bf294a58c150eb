// Photon budgets: a total split over lights by weight (largest remainder, so the
// counts add up exactly) and cut into fixed-size batches, each its own random stream.
#pragma once
#include <algorithm>
#include <cmath>
#include <cstdint>
#include <utility>
#include <vector>

namespace penumbra {

// Counts proportional to `weights` (>= 0) summing to exactly `total` (or all 0
// when no weight is positive). Ties in the remainders go to the lower index.
// A NaN or infinite weight (the loader refuses the lights that would give one) counts
// as 0: inf / inf would make a NaN share, and casting that to a count is undefined.
inline std::vector<uint64_t> splitByWeight(const std::vector<double>& weights, uint64_t total) {
  auto usable = [](double w) { return std::isfinite(w) ? std::max(0.0, w) : 0.0; };
  double sum = 0.0;
  for (double w : weights) sum += usable(w);
  std::vector<uint64_t> count(weights.size(), 0);
  if (!(sum > 0.0) || !std::isfinite(sum) || total == 0) return count;
  std::vector<std::pair<double, size_t>> remainders;
  uint64_t given = 0;
  for (size_t l = 0; l < weights.size(); ++l) {
    const double share = std::min(static_cast<double>(total), total * (usable(weights[l]) / sum));
    count[l] = static_cast<uint64_t>(share);
    given += count[l];
    if (usable(weights[l]) > 0.0) remainders.push_back({share - count[l], l});
  }
  std::stable_sort(remainders.begin(), remainders.end(),
                   [](const auto& a, const auto& b) { return a.first > b.first; });
  for (size_t i = 0; given < total && i < remainders.size(); ++i, ++given) ++count[remainders[i].second];
  return count;
}

// A run of one light's photons: its `index`-th batch, photons [first, first + count)
// of that light's sequence.
struct PhotonBatch {
  uint32_t light;
  uint64_t count;
  uint64_t index = 0;
  uint64_t first = 0;
};

inline std::vector<PhotonBatch> makeBatches(const std::vector<uint64_t>& perLight, uint32_t batchSize) {
  std::vector<PhotonBatch> batches;
  for (uint32_t l = 0; l < perLight.size(); ++l) {
    for (uint64_t done = 0; done < perLight[l]; done += batchSize) {
      batches.push_back({l, std::min<uint64_t>(batchSize, perLight[l] - done), done / batchSize, done});
    }
  }
  return batches;
}

// The random stream of a batch, keyed by its light and its index within that light,
// so a light's first n photons are the same whatever the budget of the other lights
// (emit/photon_prefix.h reuses them). Light 0 keeps the plain batch index.
inline uint64_t batchStreamKey(const PhotonBatch& batch) {
  return batch.index + (static_cast<uint64_t>(batch.light) << 40);
}

}  // namespace penumbra
