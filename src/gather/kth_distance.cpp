// Exact k-th nearest distances for a few probes: the photons are counting-sorted
// into a uniform grid of about count / 8 cells, and each probe visits cubes of cells
// of growing half-width until every photon outside the cube is provably farther than
// its k-th nearest so far.
#include "gather/kth_distance.h"
#include <algorithm>
#include <cmath>
#include <cstdint>

namespace penumbra {

namespace {

struct Grid {
  Vec3 lo{0.0f};
  float cell = 1.0f;
  int64_t n[3] = {1, 1, 1};
  std::vector<uint32_t> start;  // per cell and one past: its first photon in `order`
  std::vector<uint32_t> order;  // photon indices, cell by cell

  int64_t axisCell(float x, int axis) const {
    const float f = (x - lo[axis]) / cell;
    if (!(f > 0.0f)) return 0;  // NaN too
    return f >= float(n[axis] - 1) ? n[axis] - 1 : static_cast<int64_t>(f);
  }
  size_t index(int64_t x, int64_t y, int64_t z) const { return size_t((z * n[1] + y) * n[0] + x); }
};

const Vec3& positionAt(const Vec3* positions, size_t stride, size_t i) {
  return *reinterpret_cast<const Vec3*>(reinterpret_cast<const char*>(positions) + i * stride);
}

Grid binPhotons(const Vec3* positions, size_t count, size_t stride) {
  Grid g;
  Vec3 lo(kInf), hi(-kInf);
  for (size_t i = 0; i < count; ++i) {
    const Vec3& p = positionAt(positions, stride, i);
    lo = glm::min(lo, p);
    hi = glm::max(hi, p);
  }
  Vec3 extent = hi - lo;
  // Non-finite positions: one cell, searched whole.
  if (!std::isfinite(extent.x + extent.y + extent.z)) extent = Vec3(0.0f);
  const double target = std::max(1.0, double(count) / 8.0);
  // Photons lie on surfaces, so a flat box is common: grow the cell from the widest
  // extent's share until the grid holds no more than the target number of cells.
  float cell = std::max({extent.x, extent.y, extent.z, 1e-30f}) / static_cast<float>(std::cbrt(target));
  auto cells = [&](float h) {
    double total = 1.0;
    for (int a = 0; a < 3; ++a) total *= std::max(1.0, std::ceil(double(extent[a]) / h));
    return total;
  };
  while (cells(cell) > target) cell *= 1.25f;
  while (cell > 1e-30f && cells(cell * 0.8f) <= target) cell *= 0.8f;
  g.lo = lo;
  g.cell = cell;
  for (int a = 0; a < 3; ++a) g.n[a] = std::max<int64_t>(1, static_cast<int64_t>(std::ceil(extent[a] / cell)));
  const size_t total = size_t(g.n[0] * g.n[1] * g.n[2]);
  std::vector<uint32_t> cellOf(count);
  g.start.assign(total + 1, 0);
  for (size_t i = 0; i < count; ++i) {
    const Vec3& p = positionAt(positions, stride, i);
    cellOf[i] = static_cast<uint32_t>(g.index(g.axisCell(p.x, 0), g.axisCell(p.y, 1), g.axisCell(p.z, 2)));
    ++g.start[cellOf[i] + 1];
  }
  for (size_t c = 0; c < total; ++c) g.start[c + 1] += g.start[c];
  g.order.resize(count);
  std::vector<uint32_t> next(g.start.begin(), g.start.end() - 1);
  for (size_t i = 0; i < count; ++i) g.order[next[cellOf[i]]++] = static_cast<uint32_t>(i);
  return g;
}

// The k smallest squared distances so far, as a max-heap.
float kthAt(const Grid& g, const Vec3* positions, size_t stride, const Vec3& q, size_t k, std::vector<float>& heap) {
  heap.clear();
  const int64_t c[3] = {g.axisCell(q.x, 0), g.axisCell(q.y, 1), g.axisCell(q.z, 2)};
  const int64_t widest = std::max({g.n[0], g.n[1], g.n[2]});
  for (int64_t s = 0; s <= widest; ++s) {
    // The shell of cells at Chebyshev distance s from the probe's cell.
    const int64_t lo[3] = {std::max<int64_t>(c[0] - s, 0), std::max<int64_t>(c[1] - s, 0), std::max<int64_t>(c[2] - s, 0)};
    const int64_t hi[3] = {std::min(c[0] + s, g.n[0] - 1), std::min(c[1] + s, g.n[1] - 1), std::min(c[2] + s, g.n[2] - 1)};
    auto visit = [&](int64_t x, int64_t y, int64_t z) {
      const size_t cell = g.index(x, y, z);
      for (uint32_t e = g.start[cell]; e < g.start[cell + 1]; ++e) {
        const Vec3& p = positionAt(positions, stride, g.order[e]);
        float d2 = 0.0f;  // nanoflann's L2: differences squared and summed in axis order
        for (int a = 0; a < 3; ++a) {
          const float diff = q[a] - p[a];
          d2 += diff * diff;
        }
        if (heap.size() < k) {
          heap.push_back(d2);
          std::push_heap(heap.begin(), heap.end());
        } else if (d2 < heap.front()) {
          std::pop_heap(heap.begin(), heap.end());
          heap.back() = d2;
          std::push_heap(heap.begin(), heap.end());
        }
      }
    };
    for (int64_t z = lo[2]; z <= hi[2]; ++z) {
      for (int64_t y = lo[1]; y <= hi[1]; ++y) {
        if (std::abs(z - c[2]) == s || std::abs(y - c[1]) == s) {
          for (int64_t x = lo[0]; x <= hi[0]; ++x) visit(x, y, z);
        } else {
          // Inside the cube's y-z cross-section: only its two x faces are on the shell.
          if (c[0] - s >= 0) visit(c[0] - s, y, z);
          if (s > 0 && c[0] + s < g.n[0]) visit(c[0] + s, y, z);
        }
      }
    }
    // Every photon outside the cube lies beyond its nearest open face (a face on the
    // grid's edge has nothing beyond it).
    double clear = kInf;
    bool covered = true;
    for (int a = 0; a < 3; ++a) {
      if (c[a] - s > 0) {
        clear = std::min(clear, double(q[a]) - (double(g.lo[a]) + double(c[a] - s) * g.cell));
        covered = false;
      }
      if (c[a] + s < g.n[a] - 1) {
        clear = std::min(clear, double(g.lo[a]) + double(c[a] + s + 1) * g.cell - double(q[a]));
        covered = false;
      }
    }
    if (covered) break;
    // A margin for the float sums: an outside photon's computed distance cannot
    // undercut the true one by this much.
    if (heap.size() == k && clear > 0.0 && double(heap.front()) < clear * clear * (1.0 - 1e-5)) break;
  }
  return heap.empty() ? 0.0f : std::sqrt(heap.front());
}

}  // namespace

std::vector<float> kthNearestDistances(const Vec3* positions, size_t count, size_t stride,
                                       const std::vector<Vec3>& probes, size_t k) {
  std::vector<float> out(probes.size(), 0.0f);
  if (count == 0 || k == 0) return out;
  const Grid grid = binPhotons(positions, count, stride);
  std::vector<float> heap;
  heap.reserve(k);
  for (size_t i = 0; i < probes.size(); ++i) out[i] = kthAt(grid, positions, stride, probes[i], k, heap);
  return out;
}

}  // namespace penumbra
