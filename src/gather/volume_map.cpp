// Building the volume photon map's sparse grid and its radius rule (gather/volume_map.h).
#include "gather/volume_map.h"
#include "core/error.h"
#include <fmt/format.h>
#include <limits>
#include <utility>

namespace penumbra {
namespace {

// The cell (VolumePhotonMap::kCellPhotons) is four times the default k's beam: fewer,
// longer rows beat tighter bounds (bench_volume measures the choice).
// The radius rule's cells hold about this many photons where a typical photon lies.
constexpr double kDensityCellPhotons = 8.0;
// Cells per axis at most, so a cell's key (z ny + y) nx + x fits 63 bits.
constexpr double kMaxAxisCells = double(1 << 20);

struct Lattice {
  Vec3 lo;
  float invCell;
  int dims[3];
  uint64_t key(const Vec3& p) const {
    uint64_t c[3];
    for (int a = 0; a < 3; ++a) {
      c[a] = static_cast<uint64_t>(std::clamp(static_cast<int>((p[a] - lo[a]) * invCell), 0, dims[a] - 1));
    }
    return (c[2] * dims[1] + c[1]) * dims[0] + c[0];
  }
};

Lattice latticeOf(const Vec3& lo, const Vec3& extent, float cell) {
  const float largest = std::max({extent.x, extent.y, extent.z});
  cell = std::max(cell, static_cast<float>(largest / kMaxAxisCells));
  Lattice l{lo, 1.0f / cell, {}};
  for (int a = 0; a < 3; ++a) l.dims[a] = std::max(1, static_cast<int>(std::ceil(extent[a] / cell)));
  return l;
}

// The photon-weighted mean density over cells of size `cell`: sum of count (count - 1)
// / (N cell^3), the -1 removing the photon's own share (Poisson counts: E = lambda^2).
double typicalDensity(const PhotonArray<VolumePhoton>& photons, const Vec3& lo, const Vec3& extent, float cell) {
  const Lattice l = latticeOf(lo, extent, cell);
  std::vector<uint64_t> keys(photons.size());
  for (size_t i = 0; i < photons.size(); ++i) keys[i] = l.key(photons[i].position);
  std::sort(keys.begin(), keys.end());
  double pairs = 0.0;
  for (size_t i = 0, j; i < keys.size(); i = j) {
    for (j = i + 1; j < keys.size() && keys[j] == keys[i]; ++j) {}
    pairs += double(j - i) * double(j - i - 1);
  }
  const double c = 1.0 / l.invCell;
  return std::max(pairs, 1.0) / (double(photons.size()) * c * c * c);
}

}  // namespace

void VolumePhotonMap::build(PhotonBatches<VolumePhoton> batches, const MapBuildOptions& options) {
  const size_t n = batches.size();
  if (n > std::numeric_limits<uint32_t>::max() - 1) {
    throw InputError(fmt::format("photons: {} stored volume photons exceed the 2^32 one map can index; emit fewer", n));
  }
  photons_.clear();
  cellKeys_.clear();
  cellStart_.clear();
  rows_.clear();
  density_ = chord_ = 0.0;
  if (n == 0) return;
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

  // The radius rule's density: cells of ~8 photons at the box's mean density, then at
  // the density a typical photon sees there (dense rooms inside a sparse halo).
  const double boxVolume = double(extent.x) * extent.y * extent.z;
  double dense = typicalDensity(input, lo_, extent, float(std::cbrt(kDensityCellPhotons * boxVolume / n)));
  dense = typicalDensity(input, lo_, extent, float(std::cbrt(kDensityCellPhotons / dense)));
  density_ = dense;
  chord_ = std::cbrt(double(n) / dense);

  const Lattice grid = latticeOf(lo_, extent, radiusFor(kCellPhotons));
  cell_ = 1.0f / grid.invCell;
  invCell_ = grid.invCell;
  for (int a = 0; a < 3; ++a) dims_[a] = grid.dims[a];

  // Photons by cell key, ties in emission order; then the occupied cells and their rows.
  std::vector<std::pair<uint64_t, uint32_t>> order(n);
  for (size_t i = 0; i < n; ++i) order[i] = {grid.key(input[i].position), static_cast<uint32_t>(i)};
  std::sort(order.begin(), order.end());
  photons_.resize(n);
  size_t rows = 0;
  for (size_t i = 0; i < n; ++i) {
    photons_[i] = input[order[i].second];
    if (i == 0 || order[i].first != order[i - 1].first) {
      const uint64_t rowKey = order[i].first / uint64_t(dims_[0]);
      rows += cellKeys_.empty() || cellKeys_.back() / uint64_t(dims_[0]) != rowKey;
      cellKeys_.push_back(order[i].first);
      cellStart_.push_back(static_cast<uint32_t>(i));
    }
  }
  cellStart_.push_back(static_cast<uint32_t>(n));
  size_t slots = 16;
  while (slots < 2 * rows) slots *= 2;
  rows_.assign(slots, Row{});
  for (size_t c = 0; c < cellKeys_.size();) {
    const uint64_t rowKey = cellKeys_[c] / uint64_t(dims_[0]);
    size_t e = c + 1;
    while (e < cellKeys_.size() && cellKeys_[e] / uint64_t(dims_[0]) == rowKey) ++e;
    size_t i = hashOf(rowKey) & (slots - 1);
    while (rows_[i].key != ~uint64_t(0)) i = (i + 1) & (slots - 1);
    rows_[i] = {rowKey, static_cast<uint32_t>(c), static_cast<uint32_t>(e)};
    c = e;
  }
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
