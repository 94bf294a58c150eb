// Coarse majorants of a density grid and a ray's walk through them: the largest density
// each block of lattice cells can take, so tracking takes long steps through the thin
// or empty parts of a grid instead of stepping everywhere at the global maximum.
#pragma once
#include "core/math.h"
#include <vector>

namespace penumbra {

struct DensityGrid;  // core/media/density_grid.h

// Blocks of kMajorantBlock^3 lattice cells over the trilinear support (-1, n) per axis;
// a block's value bounds every at() inside it (the largest of the voxels it touches).
inline constexpr int kMajorantBlock = 8;
struct MajorantGrid {
  int bx = 0, by = 0, bz = 0;
  std::vector<float> maxima;  // bx * by * bz, x fastest; empty: not built
  bool empty() const { return maxima.empty(); }
  float at(int i, int j, int k) const { return maxima[(size_t(k) * by + j) * bx + i]; }
};
MajorantGrid buildMajorantGrid(const DensityGrid& g);

// The segments of [a, b] along o + t d inside the grid's support, each with a density
// bound: per block where the majorants are built, else one segment at maxDensity.
// Clipped in lattice space, so any affine worldToGrid (rotated, sheared) is exact.
class MajorantWalk {
 public:
  MajorantWalk(const DensityGrid& g, const Vec3& o, const Vec3& d, float a, float b);
  // The next segment [t0, t1) and its bound; false when the walk has left the grid.
  bool next(double& t0, double& t1, float& bound);

 private:
  const DensityGrid& grid_;
  glm::dvec3 p_{0.0}, v_{0.0};  // the ray in shifted lattice space: support (0, n + 1)
  double t_ = 0.0, end_ = 0.0;  // what is left of the clipped segment
  glm::ivec3 cell_{0}, step_{0};
  glm::dvec3 tNext_{0.0}, tDelta_{0.0};
  bool done_ = true;
};

}  // namespace penumbra
