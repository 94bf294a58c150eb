// Textured mesh lights: the emissive texture decoded at load (linear RGB, looked up
// where a light sample or photon lands) and the per-triangle luminance that decides
// how often each triangle is drawn, so dark parts of the texture cost no samples.
#pragma once
#include "core/bilinear.h"
#include "core/scene.h"
#include <vector>

namespace penumbra {

// The decoded texels; row 0 is the image's top (v = 0), as textures are looked up.
struct EmissionMap {
  int width = 0, height = 0;
  std::vector<Color> texels;  // linear, width x height, row after row
  UvTransform transform;      // the material's texture placement
  TextureSampling sampling;   // the texture's sampler (repeat in u and v without one)

  Color at(Vec2 uv) const {
    const auto texel = [&](int x, int y) { return texels[size_t(y) * size_t(width) + size_t(x)]; };
    return sampleTexels(width, height, transform.apply(uv), sampling, texel);
  }
};

// A mesh light's texture and its sampling tables, parallel to Light::triangles.
struct MeshEmission {
  EmissionMap map;
  std::vector<Vec2> uvs;        // 3 per triangle
  std::vector<float> density;   // per triangle: its mean texel luminance, floored (> 0)
  std::vector<float> weightCdf;  // cumulative area x density: back() is the light's W
  // Mean texel luminance over the mesh's area: below kDecorativeEmission the texture
  // only marks details, and the material glows where seen without being a light.
  float meanLuminance = 0.0f;
};

// A texture whose mean over its mesh is below this share of full emission is a mask
// of small details (lit panels, printed labels): a light made of it would spend its
// samples and photons on near-black texels for a negligible share of the light.
inline constexpr float kDecorativeEmission = 0.02f;

// The sampling tables for `map` over `triangles` (3 corners each) with `uvs` (3 per
// triangle): each triangle's mean luminance from a grid of points matched to the
// texels it covers, floored at a small share of the mesh's mean so that no texel that
// emits is left unsampled.
MeshEmission makeMeshEmission(EmissionMap map, const std::vector<Vec3>& triangles, std::vector<Vec2> uvs);

}  // namespace penumbra
