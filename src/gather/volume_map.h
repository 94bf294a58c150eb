// The volume photon map: media scattering events in a uniform grid whose x rows are
// contiguous, so a beam reads every row that passes within its radius as one run.
#pragma once
#include "core/photon.h"
#include "core/photon_batches.h"
#include "gather/kd_tree.h"
#include <algorithm>
#include <cmath>
#include <cstdint>
#include <vector>

namespace penumbra {

class VolumePhotonMap {
 public:
  // Takes ownership; sorts the photons by grid cell (a stable counting sort, so the
  // order depends only on the emission's). The cell is the radius of a 64-photon beam.
  void build(PhotonBatches<VolumePhoton> photons, const MapBuildOptions& options = {});
  bool empty() const { return photons_.empty(); }
  size_t size() const { return photons_.size(); }
  size_t memoryBytes() const { return photons_.capacity() * sizeof(VolumePhoton) + cellStart_.capacity() * 4; }
  const PhotonArray<VolumePhoton>& photons() const { return photons_; }
  float cellSize() const { return cell_; }

  // The radius rule: the beam radius at which a ray crossing the photons' region meets
  // about k of them, k = n pi r^2 L with n the photons per unit volume of the occupied
  // region and L = 2/3 V^(1/3) its mean chord (a cube's of the same volume V).
  float radiusFor(int k) const;

  // The part of [tMin, tMax] along o + t d (d unit) within `radius` of the grid's box:
  // false when none is.
  bool span(const Vec3& o, const Vec3& d, float radius, float& tMin, float& tMax) const;

  // f(photon, t, dist2) once for every photon whose projection t on the ray lies in
  // [tMin, tMax] and whose distance from it is below `radius` (a cylinder). Walks the
  // grid's z layers, then the y rows each layer's part of the beam can reach, then one
  // run of x cells per row: each cell at most once, no allocation.
  template <class F>
  void beam(const Vec3& o, const Vec3& d, float tMin, float tMax, float radius, F&& f) const;

 private:
  // The t where o + t d has grid coordinate axis in [a0, a1], intersected with [lo, hi].
  bool slab(int axis, const Vec3& g, const Vec3& gd, float a0, float a1, float& lo, float& hi) const {
    if (std::abs(gd[axis]) < 1e-12f) return g[axis] >= a0 && g[axis] <= a1 && lo <= hi;
    float t0 = (a0 - g[axis]) / gd[axis], t1 = (a1 - g[axis]) / gd[axis];
    if (t0 > t1) std::swap(t0, t1);
    lo = std::max(lo, t0);
    hi = std::min(hi, t1);
    return lo <= hi;
  }
  // The cells [first, last] of `axis` that the beam's grid coordinates over [t0, t1],
  // widened by r cells, reach; false when none is inside the grid.
  bool cellsOf(int axis, const Vec3& g, const Vec3& gd, float t0, float t1, float r, int& first, int& last) const {
    const float a = g[axis] + t0 * gd[axis], b = g[axis] + t1 * gd[axis];
    const float lo = std::floor(std::min(a, b) - r), hi = std::floor(std::max(a, b) + r);
    if (!(hi >= 0.0f) || !(lo < static_cast<float>(dims_[axis]))) return false;
    first = lo < 0.0f ? 0 : static_cast<int>(lo);
    last = std::min(dims_[axis] - 1, static_cast<int>(hi));
    return true;
  }

  PhotonArray<VolumePhoton> photons_;  // by cell: x fastest, then y, then z
  std::vector<uint32_t> cellStart_;    // cell c's photons: [cellStart_[c], cellStart_[c + 1])
  Vec3 lo_{0.0f}, hi_{0.0f};           // the grid's box
  float cell_ = 1.0f, invCell_ = 1.0f;
  int dims_[3] = {0, 0, 0};
  double density_ = 0.0, chord_ = 0.0;  // the radius rule's n and L
};

template <class F>
void VolumePhotonMap::beam(const Vec3& o, const Vec3& d, float tMin, float tMax, float radius, F&& f) const {
  float ta = tMin, tb = tMax;
  if (photons_.empty() || !(radius > 0.0f) || !span(o, d, radius, ta, tb)) return;
  // Grid coordinates along the ray; the cell walk is widened a hair past the radius,
  // so rounding never drops a photon the exact test below accepts.
  const Vec3 g = (o - lo_) * invCell_, gd = d * invCell_;
  const float r = radius * invCell_ * 1.0001f + 1e-4f, r2 = radius * radius;
  int z0, z1;
  if (!cellsOf(2, g, gd, ta, tb, r, z0, z1)) return;
  for (int z = z0; z <= z1; ++z) {
    float za = ta, zb = tb;
    int y0, y1;
    if (!slab(2, g, gd, z - r, z + 1 + r, za, zb) || !cellsOf(1, g, gd, za, zb, r, y0, y1)) continue;
    for (int y = y0; y <= y1; ++y) {
      float ya = za, yb = zb;
      int x0, x1;
      if (!slab(1, g, gd, y - r, y + 1 + r, ya, yb) || !cellsOf(0, g, gd, ya, yb, r, x0, x1)) continue;
      const size_t row = (static_cast<size_t>(z) * dims_[1] + y) * dims_[0];
      const uint32_t end = cellStart_[row + x1 + 1];
      for (uint32_t i = cellStart_[row + x0]; i < end; ++i) {
        const VolumePhoton& p = photons_[i];
        const Vec3 v = p.position - o;
        const float t = glm::dot(v, d);
        if (t < tMin || t > tMax) continue;
        const float d2 = glm::dot(v, v) - t * t;
        if (d2 < r2) f(p, t, d2);
      }
    }
  }
}

}  // namespace penumbra
