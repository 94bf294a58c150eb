// The result sets the KD-tree's searches fill (nanoflann's ResultSet interface):
// an exact bounded k-smallest selection keyed by (dist2, index), a fixed-radius
// collector into reusable buffers, and the bucket sort that orders a selection.
#pragma once
#include "core/math.h"
#include "gather/kd_tree.h"
#include <algorithm>
#include <cmath>
#include <limits>
#include <vector>

namespace penumbra::knn {

// Squared distances are >= 0 (or +0), whose IEEE bit patterns order like the values:
// (bits << 32 | index) orders by (dist2, index) with one integer compare.
inline uint64_t keyOf(float d2, uint32_t index) {
  return (static_cast<uint64_t>(floatBits(d2)) << 32) | index;
}
inline float distOf(uint64_t key) { return bitsToFloat(static_cast<uint32_t>(key >> 32)); }

// The k smallest (dist2, index) keys among the points nanoflann offers, with a
// shrinking bound. Candidates go into a buffer of `cap` (>= 2k) slots; the first time
// k are in, the bound drops to the largest of them (as nanoflann's KNNResultSet
// would), and whenever the buffer fills, nth_element keeps the k smallest and the
// bound drops to the k-th. Cheaper than KNNResultSet's insertion sort per accepted
// point, and ties are broken by index, so the answer is unique.
//
// A point is accepted iff its key < limitKey_. worst_ (what nanoflann prunes with:
// leaves test dist < worst, nodes mindist <= worst) is >= every accepted distance,
// with a little slack over the k-th so ties and nanoflann's incremental mindist
// rounding never prune a point that belongs to the answer.
class SelectResultSet {
 public:
  using DistanceType = float;
  using IndexType = uint32_t;

  // Accepts dist2 < limit (strict) until tightened.
  SelectResultSet(uint64_t* buf, size_t cap, size_t k, float limit)
      : buf_(buf), cap_(cap), k_(k), limitKey_(static_cast<uint64_t>(floatBits(limit)) << 32),
        worst_(limit) {}

  size_t size() const { return n_; }
  bool full() const { return n_ >= k_; }
  float worstDist() const { return worst_; }

  // Parts number their photons from 0: the offset makes the index global.
  void setOffset(uint32_t offset) { offset_ = offset; }

  bool addPoint(float d2, uint32_t index) {
    const uint64_t key = keyOf(d2, index + offset_);
    if (key >= limitKey_) return true;  // the bound shrank within this leaf
    buf_[n_++] = key;
    if (n_ == k_) {
      // First time k are in (after a compaction n_ is set, not incremented, to k).
      tighten(*std::max_element(buf_, buf_ + n_));
    } else if (n_ == cap_) {
      std::nth_element(buf_, buf_ + (k_ - 1), buf_ + n_);
      n_ = k_;
      tighten(buf_[k_ - 1]);
    }
    return true;
  }

  // Leaves the k smallest keys (or all, if fewer) in buf[0..size()), unordered.
  size_t select() {
    if (n_ > k_) {
      std::nth_element(buf_, buf_ + (k_ - 1), buf_ + n_);
      n_ = k_;
    }
    return n_;
  }

 private:
  void tighten(uint64_t kth) {
    // Anything not below the current k-th key can no longer make the answer.
    limitKey_ = kth;
    const float d = distOf(kth);
    worst_ = std::nextafter(d + d * 1e-5f, std::numeric_limits<float>::infinity());
  }

  uint64_t* buf_;
  size_t cap_, k_, n_ = 0;
  uint64_t limitKey_;
  float worst_;
  uint32_t offset_ = 0;
};

// Sorts keys[0..n) ascending, using tmp[0..n) and `counts` as scratch. The keys are
// in random order, where a comparison sort's branches mispredict about half the time,
// which makes std::sort slow here. Instead: a counting sort into n buckets by dist2
// relative to the largest (photons are spread over a disc or ball, so the buckets
// are balanced), then an insertion sort that only moves keys within their bucket.
// The bucket is a monotone function of dist2, so the result is exactly sorted for
// any input; degenerate inputs (all dist2 equal) merely cost more.
inline void sortKeys(uint64_t* keys, size_t n, uint64_t* tmp, std::vector<uint32_t>& counts) {
  if (n < 2) return;
  float maxD = 0.0f;
  for (size_t i = 0; i < n; ++i) maxD = std::max(maxD, distOf(keys[i]));
  const float top = static_cast<float>(n - 1);
  const float scale = static_cast<float>(n) / maxD;
  if (!(maxD > 0.0f) || !std::isfinite(scale)) {
    std::sort(keys, keys + n);
    return;
  }
  counts.assign(n + 1, 0);
  auto bucketOf = [&](uint64_t key) {
    return static_cast<uint32_t>(std::min(distOf(key) * scale, top));
  };
  for (size_t i = 0; i < n; ++i) ++counts[bucketOf(keys[i]) + 1];
  for (size_t b = 1; b <= n; ++b) counts[b] += counts[b - 1];
  for (size_t i = 0; i < n; ++i) tmp[counts[bucketOf(keys[i])]++] = keys[i];
  keys[0] = tmp[0];
  for (size_t i = 1; i < n; ++i) {
    const uint64_t v = tmp[i];
    size_t j = i;
    for (; j > 0 && keys[j - 1] > v; --j) keys[j] = keys[j - 1];
    keys[j] = v;
  }
}

// Writes keys[0..n) out as a gather (s.indices, s.dist2) and returns the largest dist2.
inline float unpackKeys(const uint64_t* keys, size_t n, GatherScratch& s) {
  float largest = 0.0f;
  for (size_t i = 0; i < n; ++i) {
    s.indices[i] = static_cast<uint32_t>(keys[i]);
    s.dist2[i] = distOf(keys[i]);
    largest = std::max(largest, s.dist2[i]);
  }
  return largest;
}

// Orders a gather left unsorted (s.indices, s.dist2 [0..n)) as a sorted knn() would:
// ascending (dist2, index).
inline void sortGathered(GatherScratch& s, size_t n) {
  if (s.keys.size() < 2 * n) s.keys.resize(2 * n);
  uint64_t* keys = s.keys.data();
  for (size_t i = 0; i < n; ++i) keys[i] = keyOf(s.dist2[i], s.indices[i]);
  sortKeys(keys, n, keys + n, s.buckets);
  unpackKeys(keys, n, s);
}

// nanoflann result set for a fixed-radius search into reusable buffers.
class WithinResultSet {
 public:
  using DistanceType = float;
  using IndexType = uint32_t;
  WithinResultSet(GatherScratch& s, float r2) : s_(s), r2_(r2) {}
  void setOffset(uint32_t offset) { offset_ = offset; }
  size_t size() const { return n_; }
  bool full() const { return true; }
  float worstDist() const { return r2_; }
  bool addPoint(float d2, uint32_t index) {
    if (d2 >= r2_) return true;
    if (n_ == s_.indices.size()) s_.reserve(std::max<size_t>(64, 2 * n_));
    s_.indices[n_] = index + offset_;
    s_.dist2[n_] = d2;
    ++n_;
    return true;
  }

 private:
  GatherScratch& s_;
  float r2_;
  size_t n_ = 0;
  uint32_t offset_ = 0;
};

}  // namespace penumbra::knn
