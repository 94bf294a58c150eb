// Building the volume photon map's grid and its radius rule (gather/volume_map.h).
#include "gather/volume_map.h"
#include "core/error.h"
#include <fmt/format.h>
#include <limits>

namespace penumbra {
namespace {

// The cell is the radius of a beam meeting this many photons: walks at the radii the
// default k and its progressive shrink ask for then test ~3x the photons they keep.
constexpr int kCellPhotons = 64;
// The occupancy lattice that measures the occupied region's volume, per axis at most.
constexpr int kOccupancyCells = 32;
// Grid cells per stored photon at most (4 B each): coarser cells past it.
constexpr double kCellsPerPhoton = 4.0;

// A box's cells of size `cell` per axis (at least 1).
void cellsFor(const Vec3& extent, float cell, int dims[3]) {
  for (int a = 0; a < 3; ++a) dims[a] = std::max(1, static_cast<int>(std::ceil(extent[a] / cell)));
}

int cellOf(const Vec3& p, const Vec3& lo, float invCell, const int dims[3], int axis) {
  const int c = static_cast<int>((p[axis] - lo[axis]) * invCell);
  return std::clamp(c, 0, dims[axis] - 1);
}

}  // namespace

void VolumePhotonMap::build(PhotonBatches<VolumePhoton> batches, const MapBuildOptions& options) {
  const size_t n = batches.size();
  if (n > std::numeric_limits<uint32_t>::max() - 1) {
    throw InputError(fmt::format("photons: {} stored volume photons exceed the 2^32 one map can index; emit fewer", n));
  }
  photons_.clear();
  cellStart_.clear();
  density_ = chord_ = 0.0;
  if (n == 0) {
    progressAdd(options.progress, 0);
    return;
  }
  PhotonArray<VolumePhoton> input = std::move(batches).takeArray();
  Vec3 lo(kInf), hi(-kInf);
  for (const VolumePhoton& p : input) {
    lo = glm::min(lo, p.position);
    hi = glm::max(hi, p.position);
  }
  // A flat or single-point cloud still gets a box with volume.
  const float pad = 1e-3f * glm::length(hi - lo) + 1e-6f * (1.0f + glm::length(hi));
  lo_ = lo - pad;
  hi_ = hi + pad;
  const Vec3 extent = hi_ - lo_;

  // The radius rule's region: the occupied cells of a coarse lattice over the box.
  const float coarse = std::max({extent.x, extent.y, extent.z}) / kOccupancyCells;
  int od[3];
  cellsFor(extent, coarse, od);
  std::vector<uint8_t> occupied(static_cast<size_t>(od[0]) * od[1] * od[2], 0);
  size_t filled = 0;
  for (const VolumePhoton& p : input) {
    uint8_t& o = occupied[(static_cast<size_t>(cellOf(p.position, lo_, 1.0f / coarse, od, 2)) * od[1] +
                           cellOf(p.position, lo_, 1.0f / coarse, od, 1)) * od[0] +
                          cellOf(p.position, lo_, 1.0f / coarse, od, 0)];
    filled += o == 0;
    o = 1;
  }
  const double volume = double(filled) * coarse * coarse * coarse;
  density_ = double(n) / volume;
  chord_ = 2.0 / 3.0 * std::cbrt(volume);

  // The grid: cells of the 64-photon radius, coarser if the box would need too many.
  cell_ = std::max(radiusFor(kCellPhotons), 1e-6f * std::max({extent.x, extent.y, extent.z}));
  cellsFor(extent, cell_, dims_);
  while (double(dims_[0]) * dims_[1] * dims_[2] > std::max(4096.0, kCellsPerPhoton * double(n))) {
    cell_ *= 1.25f;
    cellsFor(extent, cell_, dims_);
  }
  invCell_ = 1.0f / cell_;

  // A stable counting sort by cell: x fastest, so a row's cells hold one run of photons.
  const size_t cells = static_cast<size_t>(dims_[0]) * dims_[1] * dims_[2];
  std::vector<uint32_t> cellIndex(n);
  cellStart_.assign(cells + 1, 0);
  for (size_t i = 0; i < n; ++i) {
    const Vec3& p = input[i].position;
    cellIndex[i] = static_cast<uint32_t>((static_cast<size_t>(cellOf(p, lo_, invCell_, dims_, 2)) * dims_[1] +
                                          cellOf(p, lo_, invCell_, dims_, 1)) * dims_[0] +
                                         cellOf(p, lo_, invCell_, dims_, 0));
    ++cellStart_[cellIndex[i] + 1];
  }
  for (size_t c = 0; c < cells; ++c) cellStart_[c + 1] += cellStart_[c];
  photons_.resize(n);
  std::vector<uint32_t> next(cellStart_.begin(), cellStart_.end() - 1);
  for (size_t i = 0; i < n; ++i) photons_[next[cellIndex[i]]++] = input[i];
  progressAdd(options.progress, 2 * n);
}

float VolumePhotonMap::radiusFor(int k) const {
  if (k <= 0 || !(density_ > 0.0) || !(chord_ > 0.0)) return 0.0f;
  return static_cast<float>(std::sqrt(double(k) / (kPi * density_ * chord_)));
}

bool VolumePhotonMap::span(const Vec3& o, const Vec3& d, float radius, float& tMin, float& tMax) const {
  if (photons_.empty()) return false;
  for (int a = 0; a < 3; ++a) {
    const float lo = lo_[a] - radius, hi = hi_[a] + radius;
    if (std::abs(d[a]) < 1e-12f) {
      if (o[a] < lo || o[a] > hi) return false;
      continue;
    }
    float t0 = (lo - o[a]) / d[a], t1 = (hi - o[a]) / d[a];
    if (t0 > t1) std::swap(t0, t1);
    tMin = std::max(tMin, t0);
    tMax = std::min(tMax, t1);
  }
  return tMin <= tMax;
}

}  // namespace penumbra
