// The image module's texture sampler behind a small facade: filter widths from the
// ray footprint, the material's uv placement, wrapping in u and (mostly) clamping in v.
#include "trace/texture_lookup.h"
#include "core/image_codec.h"
#include <cmath>

namespace penumbra {

struct TextureLookup::Impl {
  std::unique_ptr<TextureSampler> sampler;
};

TextureLookup::TextureLookup(const std::vector<std::string>& paths, const std::vector<bool>& data)
    : impl_(std::make_unique<Impl>()) {
  impl_->sampler = imageCodec().textures(paths, data);
}

TextureLookup::~TextureLookup() = default;

Color TextureLookup::lookup(int index, const SurfaceRecord& s, float footprint, const UvTransform& uv) const {
  // Longitude wraps across the seam; latitude stops at the poles, unless the texture
  // repeats in v.
  const bool clampV = uv.scale.y == 1.0f && uv.scalesOnly();
  // The footprint scales with the transform; a rotation only turns it.
  const float du = footprint * s.uvPerWorld.x * std::abs(uv.scale.x);
  const float dv = footprint * s.uvPerWorld.y * std::abs(uv.scale.y);
  const Vec2 at = uv.scalesOnly() ? s.uv * uv.scale : uv.apply(s.uv);
  return impl_->sampler->sample(index, at.x, at.y, du, dv, clampV);
}

}  // namespace penumbra
