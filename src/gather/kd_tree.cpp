// nanoflann KD-tree over photon records, read in place through a dataset adaptor.
#include "gather/kd_tree.h"
#include <nanoflann.hpp>

namespace penumbra {

namespace {
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
}  // namespace

template <class Photon>
struct PhotonKdTree<Photon>::Impl {
  using Cloud = PhotonCloud<Photon>;
  using Metric = nanoflann::L2_Simple_Adaptor<float, Cloud, float, uint32_t>;
  using Index = nanoflann::KDTreeSingleIndexAdaptor<Metric, Cloud, 3, uint32_t>;
  // The index holds a reference to the cloud: both live here, at a fixed heap address.
  Cloud cloud;
  std::unique_ptr<Index> index;
  size_t bytes = 0;
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
void PhotonKdTree<Photon>::build(const std::vector<Photon>& photons, size_t leafSize) {
  impl_.reset();
  if (photons.empty()) return;  // nanoflann throws on an empty bounding box
  auto impl = std::make_unique<Impl>();
  impl->cloud = {photons.data(), photons.size()};
  impl->index = std::make_unique<typename Impl::Index>(
      3, impl->cloud, nanoflann::KDTreeSingleIndexAdaptorParams(std::max<size_t>(leafSize, 1)));
  impl->bytes = impl->index->usedMemory(*impl->index);
  impl_ = std::move(impl);
}

template <class Photon>
size_t PhotonKdTree<Photon>::knn(const Vec3& p, size_t k, float maxRadius,
                                 GatherScratch& scratch) const {
  if (!impl_ || k == 0) return 0;  // KNNResultSet reads dists[k-1]: k = 0 is not allowed
  k = std::min(k, impl_->cloud.count);  // more slots than photons would only cost memory
  scratch.reserve(k);
  nanoflann::KNNResultSet<float, uint32_t, size_t> result(k);
  result.init(scratch.indices.data(), scratch.dist2.data());
  // init() puts +max in the last slot, which is what the search prunes against until
  // k photons are in; putting r^2 there instead turns it into a radius-bounded kNN
  // (a photon is accepted only if dist2 < r^2) with no extra pass.
  if (maxRadius > 0.0f) scratch.dist2[k - 1] = maxRadius * maxRadius;
  const float query[3] = {p.x, p.y, p.z};
  impl_->index->findNeighbors(result, query, nanoflann::SearchParams());
  return result.size();
}

template <class Photon>
size_t PhotonKdTree<Photon>::memoryBytes() const {
  return impl_ ? impl_->bytes + sizeof(Impl) + sizeof(typename Impl::Index) : 0;
}

template class PhotonKdTree<ShadowPhoton>;
template class PhotonKdTree<IndirectPhoton>;

}  // namespace penumbra
