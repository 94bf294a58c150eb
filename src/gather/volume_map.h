// The volume photon map: media scattering events in a sparse uniform grid whose x rows
// are contiguous, so a beam reads every row that passes within its radius as one run.
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
  // The grid's cell: the radius of a beam meeting this many photons (so a beam across
  // the photons' region walks about sqrt(pi N / kCellPhotons) cells).
  static constexpr int kCellPhotons = 400;
  // Takes ownership; sorts the photons by grid cell (ties in emission order). Only
  // occupied cells are kept, rows found by hash: a halo of photons far from the rest
  // (light leaving a room into fog that fills the scene) costs memory per photon, not
  // per cell of its box.
  void build(PhotonBatches<VolumePhoton> photons, const MapBuildOptions& options = {});
  bool empty() const { return photons_.empty(); }
  size_t size() const { return photons_.size(); }
  size_t memoryBytes() const {
    return photons_.capacity() * sizeof(VolumePhoton) + cellStart_.capacity() * 4 + cellKeys_.capacity() * 8 +
           rows_.capacity() * sizeof(Row);
  }
  const PhotonArray<VolumePhoton>& photons() const { return photons_; }
  float cellSize() const { return cell_; }

  // The radius rule: the beam radius at which a ray crossing the photons' region meets
  // about k of them, k = n pi r^2 L, with n the density a typical photon sees (the
  // photon-weighted mean over cells holding ~8) and L = (N / n)^(1/3) the side of a
  // cube holding all N photons at it (a camera ray crossing a room of fog).
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
  // The t where o + t d has grid coordinate axis in [a0, a1], intersected with [lo, hi]
  // (inv: 1 / gd, per axis).
  static bool slab(int axis, const Vec3& g, const Vec3& gd, const Vec3& inv, float a0, float a1, float& lo,
                   float& hi) {
    if (std::abs(gd[axis]) < 1e-12f) return g[axis] >= a0 && g[axis] <= a1 && lo <= hi;
    float t0 = (a0 - g[axis]) * inv[axis], t1 = (a1 - g[axis]) * inv[axis];
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
    last = static_cast<int>(std::min(hi, static_cast<float>(dims_[axis] - 1)));
    return true;
  }

  // A row's occupied cells: [first, last) of cellKeys_; key = z rows + y.
  struct Row {
    uint64_t key = ~uint64_t(0);
    uint32_t first = 0, last = 0;
  };
  const Row* row(uint64_t key) const {
    for (size_t i = hashOf(key) & (rows_.size() - 1);; i = (i + 1) & (rows_.size() - 1)) {
      if (rows_[i].key == key) return &rows_[i];
      if (rows_[i].key == ~uint64_t(0)) return nullptr;
    }
  }
  static size_t hashOf(uint64_t k) { return static_cast<size_t>((k * 0x9E3779B97F4A7C15ull) >> 20); }

  PhotonArray<VolumePhoton> photons_;  // by cell: x fastest, then y, then z
  std::vector<uint64_t> cellKeys_;     // the occupied cells, ascending: (z ny + y) nx + x
  std::vector<uint32_t> cellStart_;    // occupied cell c's photons: [cellStart_[c], cellStart_[c + 1])
  std::vector<Row> rows_;              // open addressing, a power of two, at most half full
  Vec3 lo_{0.0f}, hi_{0.0f};           // the grid's box
  float cell_ = 1.0f, invCell_ = 1.0f;
  int dims_[3] = {0, 0, 0};
  double density_ = 0.0, chord_ = 0.0;  // the radius rule's n and L
};

template <class F>
void VolumePhotonMap::beam(const Vec3& o, const Vec3& d, float tMin, float tMax, float radius, F&& f) const {
  float ta = tMin, tb = tMax;
  if (photons_.empty() || !(radius > 0.0f) || !span(o, d, radius, ta, tb)) return;
  // Grid coordinates along the ray. A photon within r of the ray lies within
  // r sqrt(1 - d_a^2) of its projection along axis a (the offset is normal to d), so each
  // axis widens by that; a hair more, so rounding never drops a photon the exact test
  // below accepts.
  const Vec3 g = (o - lo_) * invCell_, gd = d * invCell_, inv = 1.0f / gd;
  const Vec3 w = radius * invCell_ * glm::sqrt(glm::max(Vec3(1.0f) - d * d, Vec3(0.0f))) * 1.0001f + 1e-4f;
  const float r2 = radius * radius;
  int z0, z1;
  if (!cellsOf(2, g, gd, ta, tb, w.z, z0, z1)) return;
  for (int z = z0; z <= z1; ++z) {
    float za = ta, zb = tb;
    int y0, y1;
    if (!slab(2, g, gd, inv, z - w.z, z + 1 + w.z, za, zb) || !cellsOf(1, g, gd, za, zb, w.y, y0, y1)) continue;
    for (int y = y0; y <= y1; ++y) {
      float ya = za, yb = zb;
      int x0, x1;
      if (!slab(1, g, gd, inv, y - w.y, y + 1 + w.y, ya, yb) || !cellsOf(0, g, gd, ya, yb, w.x, x0, x1)) continue;
      const uint64_t key = static_cast<uint64_t>(z) * dims_[1] + y;
      const Row* cells = row(key);
      if (!cells) continue;
      const uint64_t base = key * dims_[0];
      const uint64_t* first = cellKeys_.data() + cells->first;
      const uint64_t* last = cellKeys_.data() + cells->last;
      if (cells->last - cells->first > 1) {
        first = std::lower_bound(first, last, base + x0);
        last = std::upper_bound(first, last, base + x1);
      } else if (*first < base + x0 || *first > base + x1) {
        continue;
      }
      if (first == last) continue;
      const uint32_t end = cellStart_[last - cellKeys_.data()];
      for (uint32_t i = cellStart_[first - cellKeys_.data()]; i < end; ++i) {
        const VolumePhoton& p = photons_[i];
        const Vec3 v = p.position - o;
        const float t = glm::dot(v, d), d2 = glm::dot(v, v) - t * t;
        // One branch for the three tests: which way it goes is a coin toss per photon.
        if ((t >= tMin) & (t <= tMax) & (d2 < r2)) f(p, t, d2);
      }
    }
  }
}

}  // namespace penumbra
