// OpenImageIO TextureSystem behind a small facade: one handle per texture,
// filter widths from the ray footprint, sRGB-encoded files linearised.
#include "trace/texture_lookup.h"
#include "core/color.h"
#include "core/error.h"
#include <OpenImageIO/texture.h>
#include <algorithm>

namespace penumbra {

struct TextureLookup::Impl {
  OIIO::TextureSystem* system = nullptr;
  struct Entry {
    OIIO::TextureSystem::TextureHandle* handle;
    int channels;  // 1 (grey, replicated) or 3; grey+alpha reads only the grey channel
    bool srgb;     // stored values are sRGB-encoded: linearise after filtering
  };
  std::vector<Entry> entries;
};

namespace {
std::string oneLine(std::string s) {
  std::replace(s.begin(), s.end(), '\n', ' ');
  while (!s.empty() && s.back() == ' ') s.pop_back();
  return s;
}
}  // namespace

TextureLookup::TextureLookup(const std::vector<std::string>& paths, const std::vector<bool>& data)
    : impl_(std::make_unique<Impl>()) {
  impl_->system = OIIO::TextureSystem::create(false);
  // Files written without MIP levels still get them, built once in the cache.
  impl_->system->attribute("automip", 1);
  impl_->system->attribute("max_memory_MB", 1024.0f);
  for (size_t i = 0; i < paths.size(); ++i) {
    const std::string& path = paths[i];
    OIIO::ImageSpec spec;
    if (!impl_->system->get_imagespec(OIIO::ustring(path), 0, spec)) {
      std::string err = oneLine(impl_->system->geterror());
      OIIO::TextureSystem::destroy(impl_->system);
      throw InputError(path + ": cannot read texture: " + err);
    }
    bool integer = spec.format.basetype != OIIO::TypeDesc::FLOAT &&
                   spec.format.basetype != OIIO::TypeDesc::HALF &&
                   spec.format.basetype != OIIO::TypeDesc::DOUBLE;
    impl_->entries.push_back({impl_->system->get_texture_handle(OIIO::ustring(path)),
                              spec.nchannels >= 3 ? 3 : 1,
                              !(i < data.size() && data[i]) &&
                                  isSrgbEncoded(spec.get_string_attribute("oiio:ColorSpace"), integer)});
  }
}

TextureLookup::~TextureLookup() { OIIO::TextureSystem::destroy(impl_->system); }

Color TextureLookup::lookup(int index, const SurfaceRecord& s, float footprint, const UvTransform& uv) const {
  const Impl::Entry& e = impl_->entries[index];
  OIIO::TextureOpt opt;
  opt.swrap = OIIO::TextureOpt::WrapPeriodic;  // longitude wraps across the seam
  // Latitude stops at the poles, unless the texture repeats in v.
  const bool clampV = uv.scale.y == 1.0f && uv.scalesOnly();
  opt.twrap = clampV ? OIIO::TextureOpt::WrapClamp : OIIO::TextureOpt::WrapPeriodic;
  // The footprint scales with the transform; a rotation only turns it.
  const float du = footprint * s.uvPerWorld.x * std::abs(uv.scale.x);
  const float dv = footprint * s.uvPerWorld.y * std::abs(uv.scale.y);
  const Vec2 at = uv.scalesOnly() ? s.uv * uv.scale : uv.apply(s.uv);
  float v[3] = {1.0f, 0.0f, 1.0f};
  auto* perthread = impl_->system->get_perthread_info();
  impl_->system->texture(e.handle, perthread, opt, at.x, at.y, du, 0.0f, 0.0f, dv,
                         e.channels, v);
  Color c = e.channels == 3 ? Color(v[0], v[1], v[2]) : Color(v[0]);
  // Filtering happens on the stored (encoded) values; decoding afterwards is the
  // usual approximation and exact wherever the footprint covers one texel.
  return e.srgb ? srgbToLinear(c) : c;
}

}  // namespace penumbra
