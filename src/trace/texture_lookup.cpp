// The image module's texture sampler behind a small facade: filter widths from the
// ray footprint, the material's uv placement, and the wrap each texture reads with.
#include "trace/texture_lookup.h"
#include "core/image_codec.h"
#include <cmath>

namespace penumbra {

struct TextureLookup::Impl {
  std::unique_ptr<TextureSampler> sampler;
  std::vector<std::optional<TextureSampling>> own;  // per texture, absent = the scene file's rule
};

TextureLookup::TextureLookup(const std::vector<std::string>& paths, const std::vector<bool>& data,
                             const std::vector<std::optional<TextureSampling>>& samplers)
    : impl_(std::make_unique<Impl>()) {
  impl_->sampler = imageCodec().textures(paths, data);
  impl_->own = samplers;
  impl_->own.resize(paths.size());
}

TextureLookup::~TextureLookup() = default;

Color TextureLookup::lookup(int index, const SurfaceRecord& s, float footprint, const UvTransform& uv) const {
  const std::optional<TextureSampling>& own = impl_->own[size_t(index)];
  TextureSampling how;
  if (own) {
    how = *own;
  } else if (uv.scale.y == 1.0f && uv.scalesOnly()) {
    // Longitude wraps across the seam; latitude stops at the poles, unless the
    // texture repeats in v.
    how.wrapT = TextureWrap::ClampToEdge;
  }
  // The footprint scales with the transform; a rotation only turns it.
  const float du = footprint * s.uvPerWorld.x * std::abs(uv.scale.x);
  const float dv = footprint * s.uvPerWorld.y * std::abs(uv.scale.y);
  const Vec2 at = uv.scalesOnly() ? s.uv * uv.scale : uv.apply(s.uv);
  return impl_->sampler->sample(index, at.x, at.y, du, dv, how);
}

}  // namespace penumbra
