// nanoflann KD-tree over photon records, read in place through a dataset adaptor,
// queried with an exact bounded-selection result set and per-thread search hints.
#include "gather/kd_tree.h"
#include "gather/knn_result_sets.h"
#include "gather/morton.h"
#include "core/mapped_memory.h"
#include <nanoflann.hpp>
// This file relies on nanoflann 1.4.x internals: the index array `vAcc`,
// `SearchParams`, `SkipInitialBuildIndex`, and result sets without `sort()`.
// 1.5 and 1.6 renamed or changed each of them (Debian 12's 1.4.3 says 0x142).
static_assert(NANOFLANN_VERSION >= 0x142 && NANOFLANN_VERSION < 0x150,
              "penumbra's KD tree needs nanoflann 1.4.x (vAcc, SearchParams, SkipInitialBuildIndex, "
              "result sets without sort()); 1.5+ renamed or changed them");
#include <tbb/blocked_range.h>
#include <tbb/enumerable_thread_specific.h>
#include <tbb/parallel_for.h>
#include <tbb/parallel_invoke.h>
#include <algorithm>
#include <cmath>
#include <cstring>
#include <limits>

namespace penumbra {

namespace {
using namespace knn;
// nanoflann's dataset interface over the photon array: positions are read straight
// from the records, nothing is copied.
template <class Photon>
struct PhotonCloud {
  const Photon* data = nullptr;
  size_t count = 0;
  size_t kdtree_get_point_count() const { return count; }
  float kdtree_get_pt(uint32_t i, size_t dim) const { return (&data[i].position.x)[dim]; }
  template <class BBox>
  bool kdtree_get_bbox(BBox&) const { return false; }
};

// Candidate buffer slots per query, as a multiple of k: larger means fewer
// nth_element passes but a bound that tightens later.
constexpr size_t kBufferFactor = 4;
// The hint ball's radius: the nearest recent query's k-th-neighbour distance r plus
// the step to it (a ball that provably holds >= k photons), but at most r grown by
// this margin (when the step is long, the density is likely similar and a smaller
// ball prunes far better; if it holds < k photons, the search is repeated).
constexpr float kHintMargin = 0.2f;
// A recent query farther than this many radii is another stream: record the new
// query in a fresh entry instead of overwriting that one.
constexpr float kSameStreamSteps = 4.0f;
// A hint ball that held < k photons: retry once at twice the radius, then unbounded.
constexpr float kRetryGrowth2 = 4.0f;

// Photons per part of a tree: nanoflann 1.4.3 builds single-threaded, so a map is
// split into Morton-ordered ranges of about this many photons, built side by side
// and searched as one. The count depends only on the photon count, never on the
// thread count, so the storage order and every answer are the same for any threads.
constexpr size_t kPhotonsPerPart = 1 << 18;
constexpr size_t kMaxParts = 16;
size_t partCount(size_t n) { return std::clamp<size_t>((n + kPhotonsPerPart - 1) / kPhotonsPerPart, 1, kMaxParts); }


// Arranges photons[0..count) in place so that part i of `parts` (the range
// [count i / parts, count (i + 1) / parts)) holds a spatially compact block: a
// median split on the widest axis, recursively, halves of the part list in
// parallel. Linear passes and swaps only, no copy; the result depends only on the
// input order, never on the thread count (each half is split by one thread).
template <class Photon>
void splitIntoParts(Photon* photons, size_t count, size_t parts, size_t first, size_t last) {
  if (last - first < 2) return;
  const size_t begin = count * first / parts, end = count * last / parts;
  const size_t midPart = (first + last) / 2, mid = count * midPart / parts;
  Vec3 lo(kInf), hi(-kInf);
  for (size_t i = begin; i < end; ++i) {
    lo = glm::min(lo, photons[i].position);
    hi = glm::max(hi, photons[i].position);
  }
  const Vec3 extent = hi - lo;
  const int axis = extent.x >= extent.y && extent.x >= extent.z ? 0 : (extent.y >= extent.z ? 1 : 2);
  std::nth_element(photons + begin, photons + mid, photons + end,
                   [axis](const Photon& a, const Photon& b) { return a.position[axis] < b.position[axis]; });
  tbb::parallel_invoke([&] { splitIntoParts(photons, count, parts, first, midPart); },
                       [&] { splitIntoParts(photons, count, parts, midPart, last); });
}
}  // namespace

template <class Photon>
struct PhotonKdTree<Photon>::Impl {
  using Cloud = PhotonCloud<Photon>;
  using Metric = nanoflann::L2_Simple_Adaptor<float, Cloud, float, uint32_t>;
  using Index = nanoflann::KDTreeSingleIndexAdaptor<Metric, Cloud, 3, uint32_t>;
  // One contiguous range of the photon array and its own tree. The index holds a
  // reference to the cloud: parts live at fixed heap addresses (the array never grows).
  struct Part {
    Cloud cloud;
    std::unique_ptr<Index> index;
    uint32_t offset = 0;
    Vec3 lo{kInf}, hi{-kInf};  // the part's bounding box
  };
  std::vector<Part> parts;
  size_t count = 0;
  size_t bytes = 0;

  // The parts in the order to search them (nearest box first) with their squared
  // box distances; returns how many.
  size_t order(const float q[3], uint8_t* ids, float* d2) const {
    const size_t n = parts.size();
    for (size_t i = 0; i < n; ++i) {
      const Vec3 p(q[0], q[1], q[2]);
      const Vec3 d = glm::max(glm::max(parts[i].lo - p, p - parts[i].hi), Vec3(0.0f));
      float v = glm::dot(d, d);
      size_t j = i;  // insertion sort: at most kMaxParts entries
      for (; j > 0 && d2[j - 1] > v; --j) {
        d2[j] = d2[j - 1];
        ids[j] = ids[j - 1];
      }
      d2[j] = v;
      ids[j] = static_cast<uint8_t>(i);
    }
    return n;
  }

  // Offers every part whose box may hold a point the result set still accepts.
  template <class Result>
  void searchParts(const float q[3], Result& result) const {
    uint8_t ids[kMaxParts];
    float d2[kMaxParts];
    const size_t n = order(q, ids, d2);
    for (size_t i = 0; i < n; ++i) {
      if (d2[i] > result.worstDist()) break;  // sorted: every later box is farther
      const Part& part = parts[ids[i]];
      result.setOffset(part.offset);
      part.index->findNeighbors(result, q, nanoflann::SearchParams());
    }
  }

  // One bounded search from scratch: the k smallest keys with dist2 < limit.
  size_t search(const float q[3], size_t k, size_t cap, float limit, GatherScratch& s) const {
    SelectResultSet result(s.keys.data(), cap, k, limit);
    searchParts(q, result);
    return result.select();
  }
};

template <class Photon>
PhotonKdTree<Photon>::PhotonKdTree() = default;
template <class Photon>
PhotonKdTree<Photon>::~PhotonKdTree() = default;
template <class Photon>
PhotonKdTree<Photon>::PhotonKdTree(PhotonKdTree&&) noexcept = default;
template <class Photon>
PhotonKdTree<Photon>& PhotonKdTree<Photon>::operator=(PhotonKdTree&&) noexcept = default;

template <class Photon>
void PhotonKdTree<Photon>::build(Photon* photons, size_t count, size_t leafSize, bool split,
                                 ProgressCounter* progress, bool reorder) {
  impl_.reset();
  if (count == 0) return;  // nanoflann throws on an empty bounding box
  auto impl = std::make_unique<Impl>();
  impl->count = count;
  const size_t parts = partCount(count);
  if (split) splitIntoParts(photons, count, parts, 0, parts);
  impl->parts.resize(parts);
  // Leaf order by a gather through one part-sized buffer per thread: independent
  // loads, where following the permutation's cycles in place waited on one cache
  // miss per photon, which dominated the build.
  const size_t largestPart = (count + parts - 1) / parts;
  tbb::enumerable_thread_specific<PhotonArray<Photon>> leafOrder(
      [&] { return PhotonArray<Photon>(reorder ? largestPart : 0); });
  tbb::parallel_for(size_t(0), parts, [&](size_t i) {
    typename Impl::Part& part = impl->parts[i];
    const size_t begin = count * i / parts, end = count * (i + 1) / parts;
    part.offset = static_cast<uint32_t>(begin);
    part.cloud = {photons + begin, end - begin};
    const nanoflann::KDTreeSingleIndexAdaptorParams params(
        std::max<size_t>(leafSize, 1), nanoflann::KDTreeSingleIndexAdaptorFlags::SkipInitialBuildIndex);
    part.index = std::make_unique<typename Impl::Index>(3, part.cloud, params);
    // nanoflann zero-fills its index array (4 B per photon, malloc'd) page by page,
    // and first-touch page faults dominate that on this project's VMs: populate it
    // in one call first.
    part.index->vAcc.reserve(end - begin);
    prefaultForWrite(part.index->vAcc.data(), (end - begin) * sizeof(uint32_t));
    part.index->buildIndex();
    // The nodes address vAcc positions, not photons: storing photon vAcc[j] at j and
    // making vAcc the identity leaves the tree valid and every leaf contiguous.
    auto& vAcc = part.index->vAcc;
    Photon* local = photons + begin;
    const size_t n = end - begin;
    if (!reorder) {
      for (size_t j = 0; j < n; ++j) {
        part.lo = glm::min(part.lo, local[j].position);
        part.hi = glm::max(part.hi, local[j].position);
      }
      progressAdd(progress, n);
      return;
    }
    Photon* buffer = leafOrder.local().data();
    for (size_t j = 0; j < n; ++j) buffer[j] = local[vAcc[j]];
    for (size_t j = 0; j < n; ++j) {
      local[j] = buffer[j];
      part.lo = glm::min(part.lo, buffer[j].position);
      part.hi = glm::max(part.hi, buffer[j].position);
      vAcc[j] = static_cast<uint32_t>(j);
    }
    progressAdd(progress, n);
  });
  // An exception in a task around this build (another light's tree, out of memory)
  // cancels the parts not yet started, and propagates from there: stay empty.
  for (const auto& part : impl->parts)
    if (!part.index) return;
  for (const auto& part : impl->parts) impl->bytes += part.index->usedMemory(*part.index);
  impl_ = std::move(impl);
}

template <class Photon>
size_t PhotonKdTree<Photon>::knn(const Vec3& p, size_t k, float maxRadius,
                                 GatherScratch& scratch, bool sorted) const {
  if (!impl_ || k == 0) return 0;
  k = std::min(k, impl_->count);  // more slots than photons would only cost memory
  scratch.reserve(k);
  const size_t cap = std::max<size_t>(kBufferFactor * k, 2 * k);
  if (scratch.keys.size() < cap + k) scratch.keys.resize(cap + k);  // + k: sort scratch
  const float inf = std::numeric_limits<float>::infinity();
  const float limit = maxRadius > 0.0f ? maxRadius * maxRadius : inf;
  const float q[3] = {p.x, p.y, p.z};

  // The hint ball (see GatherScratch). If it holds >= k photons, its k smallest keys
  // are the global answer, since everything outside is farther; if not, retry larger.
  GatherScratch::Hint* hint = nullptr;
  unsigned entry = 0;
  float hinted = -1.0f;  // squared radius; < 0: no hint
  if (scratch.forcedHintRadius >= 0.0f) {
    hinted = scratch.forcedHintRadius * scratch.forcedHintRadius;
  } else if (scratch.useHints) {
    hint = &scratch.hintFor(impl_.get(), k);
    float best = inf;
    for (unsigned e = 0; e < GatherScratch::kHintEntries; ++e) {
      if (hint->r[e] < 0.0f) continue;
      const Vec3 d = p - hint->p[e];
      const float dd = glm::dot(d, d);
      if (dd < best) {
        best = dd;
        entry = e;
      }
    }
    bool sameStream = false;
    if (best < inf) {
      const float rp = hint->r[entry], step = std::sqrt(best);
      const float r = std::min(rp + step, rp * (1.0f + kHintMargin));
      hinted = std::nextafter(r * r * 1.0002f, inf);  // slack for rounding; > 0 even for r = 0
      sameStream = step <= kSameStreamSteps * rp;
    }
    if (!sameStream) {
      entry = hint->next;
      hint->next = (hint->next + 1) % GatherScratch::kHintEntries;
    }
  }
  size_t n;
  if (hinted >= 0.0f && hinted < limit) {
    ++scratch.hintedQueries;
    n = impl_->search(q, k, cap, hinted, scratch);
    if (n < k) {
      ++scratch.hintReruns;
      if (hinted * kRetryGrowth2 < limit) n = impl_->search(q, k, cap, hinted * kRetryGrowth2, scratch);
      if (n < k) n = impl_->search(q, k, cap, limit, scratch);
    }
  } else {
    n = impl_->search(q, k, cap, limit, scratch);
  }

  uint64_t* keys = scratch.keys.data();
  if (sorted) sortKeys(keys, n, keys + n, scratch.buckets);
  const float kth = unpackKeys(keys, n, scratch);
  if (hint && n == k) {  // fewer than k (within maxRadius): nothing learnt
    hint->p[entry] = p;
    hint->r[entry] = std::sqrt(kth);
  }
  return n;
}


template <class Photon>
size_t PhotonKdTree<Photon>::within(const Vec3& p, float radius, GatherScratch& scratch) const {
  if (!impl_ || !(radius > 0.0f)) return 0;
  const float q[3] = {p.x, p.y, p.z};
  WithinResultSet result(scratch, radius * radius);
  impl_->searchParts(q, result);
  return result.size();
}

template <class Photon>
size_t PhotonKdTree<Photon>::memoryBytes() const {
  return impl_ ? impl_->bytes + sizeof(Impl) +
                     impl_->parts.size() * (sizeof(typename Impl::Part) + sizeof(typename Impl::Index))
               : 0;
}

template class PhotonKdTree<ShadowPhoton>;
template class PhotonKdTree<IndirectPhoton>;

}  // namespace penumbra
