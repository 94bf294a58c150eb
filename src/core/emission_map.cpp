// The sampling tables of a textured mesh light: each triangle's mean luminance over
// the texels it covers, and the cumulative weights that draw triangles by it.
#include "core/emission_map.h"
#include <algorithm>
#include <cmath>

namespace penumbra {

namespace {

// Samples per triangle side: the grid of n^2 sub-triangles has about one point per
// texel the triangle covers, up to 16^2 points.
constexpr int kMaxGrid = 16;

// A floor on each triangle's density, as a share of the mesh's mean: a triangle whose
// grid points all landed on black texels may still hold a few that emit.
constexpr float kDensityFloor = 0.01f;

// Mean luminance over triangle (a, b, c) in uv: the centroids of its n^2 sub-triangles.
float meanLuminance(const EmissionMap& map, const Vec2* uv) {
  const Vec2 e1 = uv[1] - uv[0], e2 = uv[2] - uv[0];
  const float texels = 0.5f * std::abs(e1.x * e2.y - e1.y * e2.x) * float(map.width) * float(map.height);
  const int n = std::clamp(static_cast<int>(std::ceil(std::sqrt(std::isfinite(texels) ? texels : 1.0f))), 1, kMaxGrid);
  const float step = 1.0f / float(n);
  float sum = 0.0f;
  for (int i = 0; i < n; ++i) {
    for (int j = 0; i + j < n; ++j) {
      // The upright sub-triangle at (i, j), then the inverted one beside it.
      sum += luminance(map.at(uv[0] + ((float(i) + 1.0f / 3.0f) * step) * e1 + ((float(j) + 1.0f / 3.0f) * step) * e2));
      if (i + j + 1 < n) {
        sum += luminance(map.at(uv[0] + ((float(i) + 2.0f / 3.0f) * step) * e1 + ((float(j) + 2.0f / 3.0f) * step) * e2));
      }
    }
  }
  return std::max(0.0f, sum / float(n * n));
}

}  // namespace

MeshEmission makeMeshEmission(EmissionMap map, const std::vector<Vec3>& triangles, std::vector<Vec2> uvs) {
  MeshEmission e;
  e.map = std::move(map);
  e.uvs = std::move(uvs);
  const size_t count = triangles.size() / 3;
  std::vector<float> area(count);
  e.density.resize(count);
  double weighted = 0.0, total = 0.0;
  for (size_t i = 0; i < count; ++i) {
    const Vec3* t = &triangles[3 * i];
    area[i] = 0.5f * glm::length(glm::cross(t[1] - t[0], t[2] - t[0]));
    e.density[i] = meanLuminance(e.map, &e.uvs[3 * i]);
    weighted += double(area[i]) * e.density[i];
    total += area[i];
  }
  e.meanLuminance = total > 0.0 ? float(weighted / total) : 0.0f;
  const float floor = std::max(kDensityFloor * e.meanLuminance, 1e-6f);
  float sum = 0.0f;
  e.weightCdf.resize(count);
  for (size_t i = 0; i < count; ++i) {
    e.density[i] = std::max(e.density[i], floor);
    sum += area[i] * e.density[i];
    e.weightCdf[i] = sum;
  }
  return e;
}

}  // namespace penumbra
