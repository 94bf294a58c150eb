// Image textures through the image module (core/image_codec.h): MIP-mapped, filtered,
// wrapped by the texture's own sampler (glTF) or else by the scene file's rule:
// periodic in u (the longitude seam) and clamped in v (the poles).
#pragma once
#include "geometry/trace_scene.h"
#include <memory>
#include <optional>
#include <string>
#include <vector>

namespace penumbra {

class TextureLookup {
 public:
  // paths: Scene::textures paths, already resolved to real files; `data[i]` says
  // texture i holds values (never sRGB-decoded), absent = colours; `samplers[i]` is
  // texture i's own sampler, absent = the scene file's rule.
  explicit TextureLookup(const std::vector<std::string>& paths, const std::vector<bool>& data = {},
                         const std::vector<std::optional<TextureSampling>>& samplers = {});
  ~TextureLookup();
  // Linear RGB of texture `index` at the surface's uv; `footprint` is the world
  // width the pixel covers there, turned into a filter width in uv.
  // `uv` places the texture (material uv_scale, glTF's texture transform). Without
  // a sampler of its own, v wraps instead of clamping when `uv` does more than
  // scale by 1.
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
