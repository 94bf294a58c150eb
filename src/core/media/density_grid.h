// A density grid as rendering reads it: voxel values on a regular lattice with a
// world-to-lattice transform (io/vdb_reader fills it from an OpenVDB float grid).
#pragma once
#include "core/math.h"
#include "core/media/majorant_grid.h"
#include <cstdint>
#include <vector>

namespace penumbra {

struct DensityGrid {
  int nx = 0, ny = 0, nz = 0;   // voxels per axis
  std::vector<float> values;    // nx * ny * nz, x fastest; finite and >= 0
  // World point -> continuous lattice coordinates, voxel (i, j, k)'s centre at (i, j, k).
  glm::mat4 worldToGrid{1.0f};
  Vec3 worldLo{0.0f}, worldHi{0.0f};  // a world box holding every voxel (density 0 outside)
  float maxDensity = 0.0f;            // the majorant of every lookup: the largest value
  // Per-block majorants: the reader fills them once (buildMajorantGrid) after the values,
  // and tracking steps through thin regions at their own bound; empty: maxDensity alone.
  MajorantGrid majorants;

  float voxel(int i, int j, int k) const {
    if (i < 0 || j < 0 || k < 0 || i >= nx || j >= ny || k >= nz) return 0.0f;
    return values[(static_cast<size_t>(k) * ny + j) * nx + i];
  }
  // Trilinear between voxel centres; 0 outside the lattice.
  float at(const Vec3& world) const {
    const glm::vec4 g = worldToGrid * glm::vec4(world, 1.0f);
    const Vec3 p(g.x, g.y, g.z);
    const Vec3 f = glm::floor(p);
    const int i = static_cast<int>(f.x), j = static_cast<int>(f.y), k = static_cast<int>(f.z);
    if (!(p.x > -1.0f && p.y > -1.0f && p.z > -1.0f && p.x < nx && p.y < ny && p.z < nz)) return 0.0f;
    const Vec3 w = p - f;
    auto lerp = [](float a, float b, float t) { return a + (b - a) * t; };
    const float c00 = lerp(voxel(i, j, k), voxel(i + 1, j, k), w.x);
    const float c10 = lerp(voxel(i, j + 1, k), voxel(i + 1, j + 1, k), w.x);
    const float c01 = lerp(voxel(i, j, k + 1), voxel(i + 1, j, k + 1), w.x);
    const float c11 = lerp(voxel(i, j + 1, k + 1), voxel(i + 1, j + 1, k + 1), w.x);
    return lerp(lerp(c00, c10, w.y), lerp(c01, c11, w.y), w.z);
  }
};

}  // namespace penumbra
