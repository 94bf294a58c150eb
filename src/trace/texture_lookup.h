// Image textures through the image module (core/image_codec.h): MIP-mapped, filtered,
// periodic in u (the longitude seam) and clamped in v (the poles).
#pragma once
#include "geometry/trace_scene.h"
#include <memory>
#include <string>
#include <vector>

namespace penumbra {

class TextureLookup {
 public:
  // paths: Scene::textures paths, already resolved to real files; `data[i]` says
  // texture i holds values (never sRGB-decoded), absent = colours.
  explicit TextureLookup(const std::vector<std::string>& paths, const std::vector<bool>& data = {});
  ~TextureLookup();
  // Linear RGB of texture `index` at the surface's uv; `footprint` is the world
  // width the pixel covers there, turned into a filter width in uv.
  // `uv` places the texture (material uv_scale, glTF's texture transform); v wraps
  // instead of clamping when it is more than a scale of 1.
  Color lookup(int index, const SurfaceRecord& s, float footprint, const UvTransform& uv = {}) const;

 private:
  struct Impl;
  std::unique_ptr<Impl> impl_;
};

// A metallic-roughness material's factors at a hit: times its map's B (metallic) and
// G (roughness) channels, which are data, never sRGB-decoded.
struct MetalRough {
  float metallic, roughness;
};
inline MetalRough metalRoughAt(const Material& m, const TextureLookup& textures, const SurfaceRecord& s,
                               float footprint) {
  if (m.metalRoughTexture < 0) return {m.metallic, m.roughness};
  const Color t = textures.lookup(m.metalRoughTexture, s, footprint, m.uvTransform());
  return {m.metallic * t.b, m.roughness * t.g};
}

}  // namespace penumbra
