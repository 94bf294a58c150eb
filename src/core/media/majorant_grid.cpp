// Coarse majorants of a density grid and the ray walk through them (majorant_grid.h).
#include "core/media/majorant_grid.h"
#include "core/media/density_grid.h"
#include <algorithm>
#include <cmath>

namespace penumbra {

MajorantGrid buildMajorantGrid(const DensityGrid& g) {
  MajorantGrid m;
  if (g.nx <= 0 || g.ny <= 0 || g.nz <= 0) return m;
  // The support (-1, n) shifted to (0, n + 1): block b covers lattice [bB - 1, (b+1)B - 1),
  // where at() blends voxels bB - 1 .. (b+1)B - 1.
  const auto blocks = [](int n) { return (n + 1 + kMajorantBlock - 1) / kMajorantBlock; };
  m.bx = blocks(g.nx), m.by = blocks(g.ny), m.bz = blocks(g.nz);
  m.maxima.assign(size_t(m.bx) * m.by * m.bz, 0.0f);
  for (int k = 0; k < g.nz; ++k) {
    for (int j = 0; j < g.ny; ++j) {
      for (int i = 0; i < g.nx; ++i) {
        const float v = g.voxel(i, j, k);
        if (!(v > 0.0f)) continue;
        // Voxel i is blended into lattice points in (i - 1, i + 1): shifted (i, i + 2),
        // which lies in blocks i / B .. (i + 1) / B.
        for (int c = k / kMajorantBlock; c <= std::min((k + 1) / kMajorantBlock, m.bz - 1); ++c)
          for (int b = j / kMajorantBlock; b <= std::min((j + 1) / kMajorantBlock, m.by - 1); ++b)
            for (int a = i / kMajorantBlock; a <= std::min((i + 1) / kMajorantBlock, m.bx - 1); ++a) {
              float& slot = m.maxima[(size_t(c) * m.by + b) * m.bx + a];
              slot = std::max(slot, v);
            }
      }
    }
  }
  return m;
}

MajorantWalk::MajorantWalk(const DensityGrid& g, const Vec3& o, const Vec3& d, float a, float b) : grid_(g) {
  if (g.nx <= 0 || g.ny <= 0 || g.nz <= 0 || !(b > a)) return;
  const glm::dmat4 m(g.worldToGrid);
  p_ = glm::dvec3(m * glm::dvec4(glm::dvec3(o), 1.0)) + 1.0;
  v_ = glm::dvec3(m * glm::dvec4(glm::dvec3(d), 0.0));
  const glm::dvec3 hi(g.nx + 1, g.ny + 1, g.nz + 1);
  double t0 = a, t1 = b;
  for (int i = 0; i < 3; ++i) {
    if (v_[i] == 0.0) {
      if (!(p_[i] > 0.0 && p_[i] < hi[i])) return;
      continue;
    }
    double lo = -p_[i] / v_[i], up = (hi[i] - p_[i]) / v_[i];
    if (lo > up) std::swap(lo, up);
    t0 = std::max(t0, lo);
    t1 = std::min(t1, up);
  }
  if (!(t0 < t1)) return;
  t_ = t0, end_ = t1, done_ = false;
  if (g.majorants.empty()) return;
  const MajorantGrid& mg = g.majorants;
  const glm::ivec3 blocks(mg.bx, mg.by, mg.bz);
  const glm::dvec3 start = p_ + t0 * v_;
  for (int i = 0; i < 3; ++i) {
    cell_[i] = std::clamp(int(std::floor(start[i] / kMajorantBlock)), 0, blocks[i] - 1);
    if (v_[i] == 0.0) {
      step_[i] = 0, tNext_[i] = kInf, tDelta_[i] = kInf;
      continue;
    }
    step_[i] = v_[i] > 0.0 ? 1 : -1;
    const double boundary = double(cell_[i] + (step_[i] > 0 ? 1 : 0)) * kMajorantBlock;
    tNext_[i] = (boundary - p_[i]) / v_[i];
    tDelta_[i] = kMajorantBlock / std::abs(v_[i]);
  }
}

bool MajorantWalk::next(double& t0, double& t1, float& bound) {
  if (done_) return false;
  const MajorantGrid& mg = grid_.majorants;
  if (mg.empty()) {
    t0 = t_, t1 = end_, bound = grid_.maxDensity;
    done_ = true;
    return true;
  }
  // The axis whose block boundary comes first ends this segment.
  const int axis = tNext_.x <= tNext_.y ? (tNext_.x <= tNext_.z ? 0 : 2) : (tNext_.y <= tNext_.z ? 1 : 2);
  t0 = t_;
  t1 = std::min(tNext_[axis], end_);
  bound = mg.at(cell_.x, cell_.y, cell_.z);
  t_ = t1;
  cell_[axis] += step_[axis];
  tNext_[axis] += tDelta_[axis];
  const glm::ivec3 blocks(mg.bx, mg.by, mg.bz);
  if (t1 >= end_ || cell_[axis] < 0 || cell_[axis] >= blocks[axis]) done_ = true;
  return true;
}

}  // namespace penumbra
