// What a loaded scene's media must satisfy for the render stages (core/media/*): every
// medium index in range, coefficients finite and >= 0, g in (-1, 1), grids consistent.
#pragma once
#include "core/media/density_grid.h"
#include "core/scene.h"

#include <cmath>
#include <cstdio>
#include <cstdlib>

namespace penumbra_fuzz {

[[noreturn]] inline void mediaBroken(const char* what) {
  std::fprintf(stderr, "fuzz: media invariant broken: %s\n", what);
  std::abort();
}

// nx * ny * nz finite values >= 0, maxDensity their maximum, a finite world box.
inline void checkDensityGrid(const penumbra::DensityGrid& g) {
  if (g.nx <= 0 || g.ny <= 0 || g.nz <= 0) mediaBroken("density grid without voxels");
  if (g.values.size() != size_t(g.nx) * size_t(g.ny) * size_t(g.nz)) mediaBroken("density values != nx ny nz");
  float most = 0.0f;
  for (float v : g.values) {
    if (!(v >= 0.0f) || !std::isfinite(v)) mediaBroken("density not finite and >= 0");
    most = std::max(most, v);
  }
  if (most != g.maxDensity) mediaBroken("maxDensity is not the largest value");
  for (int a = 0; a < 3; ++a) {
    if (!std::isfinite(g.worldLo[a]) || !std::isfinite(g.worldHi[a]) || g.worldLo[a] > g.worldHi[a]) {
      mediaBroken("density world box not finite and ordered");
    }
    for (int b = 0; b < 4; ++b) {
      if (!std::isfinite(g.worldToGrid[b][a])) mediaBroken("worldToGrid not finite");
    }
  }
}

inline void checkMedia(const penumbra::Scene& scene) {
  const int n = static_cast<int>(scene.media.size());
  auto index = [&](int m) { return m == penumbra::kNoMedium || (m >= 0 && m < n); };
  auto coefficient = [](const penumbra::Color& c) {
    return std::isfinite(c.r) && std::isfinite(c.g) && std::isfinite(c.b) && c.r >= 0.0f && c.g >= 0.0f && c.b >= 0.0f;
  };
  for (const penumbra::Medium& m : scene.media) {
    if (!coefficient(m.sigmaA) || !coefficient(m.sigmaS) || !coefficient(m.emission)) {
      mediaBroken("medium coefficient not finite and >= 0");
    }
    if (!(m.g > -1.0f && m.g < 1.0f)) mediaBroken("g outside (-1, 1)");
    if (m.density) checkDensityGrid(*m.density);
  }
  if (!index(scene.sceneMedium) || !index(scene.cameraMedium)) mediaBroken("scene or camera medium out of range");
  for (const penumbra::Light& l : scene.lights) {
    if (!index(l.medium)) mediaBroken("light medium out of range");
  }
  auto interface = [&](const penumbra::MediumInterface& f) {
    if (!index(f.inside) || !index(f.outside)) mediaBroken("interface medium out of range");
    if (n == 0 && f.separates) mediaBroken("an interface in a scene without media");
  };
  for (const penumbra::Sphere& s : scene.spheres) interface(s.media);
  for (const penumbra::Sphere& s : scene.boundarySpheres) interface(s.media);
  for (const penumbra::TriangleMesh& m : scene.meshes) interface(m.media);
  for (const penumbra::TriangleMesh& m : scene.boundaryMeshes) {
    interface(m.media);
    if (!m.media.separates || m.media.inside == penumbra::kNoMedium) mediaBroken("a boundary without its medium");
  }
}

}  // namespace penumbra_fuzz
