// OpenImageIO TextureSystem behind a small facade: one handle per texture,
// filter widths from the ray footprint, 8-bit (sRGB) files linearised.
#include "trace/texture_lookup.h"
#include "core/error.h"
#include <OpenImageIO/texture.h>

namespace penumbra {

struct TextureLookup::Impl {
  OIIO::TextureSystem* system = nullptr;
  std::vector<OIIO::TextureSystem::TextureHandle*> handles;
  std::vector<bool> srgb;  // 8-bit files are sRGB-encoded; filtered values get linearised
};

namespace {
float srgbToLinear(float c) {
  return c <= 0.04045f ? c / 12.92f : std::pow((c + 0.055f) / 1.055f, 2.4f);
}
}  // namespace

TextureLookup::TextureLookup(const std::vector<std::string>& paths) : impl_(std::make_unique<Impl>()) {
  impl_->system = OIIO::TextureSystem::create(false);
  // Files written without MIP levels still get them, built once in the cache.
  impl_->system->attribute("automip", 1);
  impl_->system->attribute("max_memory_MB", 1024.0f);
  impl_->system->attribute("gray_to_rgb", 1);
  for (const std::string& path : paths) {
    OIIO::ImageSpec spec;
    if (!impl_->system->get_imagespec(OIIO::ustring(path), 0, spec)) {
      std::string err = impl_->system->geterror();
      OIIO::TextureSystem::destroy(impl_->system);
      throw InputError(path + ": cannot read texture: " + err);
    }
    impl_->handles.push_back(impl_->system->get_texture_handle(OIIO::ustring(path)));
    impl_->srgb.push_back(spec.format == OIIO::TypeDesc::UINT8);
  }
}

TextureLookup::~TextureLookup() { OIIO::TextureSystem::destroy(impl_->system); }

Color TextureLookup::lookup(int index, const SurfaceRecord& s, float footprint) const {
  OIIO::TextureOpt opt;
  opt.swrap = OIIO::TextureOpt::WrapPeriodic;  // longitude wraps across the seam
  opt.twrap = OIIO::TextureOpt::WrapClamp;     // latitude stops at the poles
  // u spans the circumference (2 pi r) and v the meridian (pi r).
  float du = footprint / (2.0f * kPi * s.radius);
  float dv = footprint / (kPi * s.radius);
  float rgb[3] = {1.0f, 0.0f, 1.0f};
  auto* perthread = impl_->system->get_perthread_info();
  impl_->system->texture(impl_->handles[index], perthread, opt, s.uv.x, s.uv.y, du, 0.0f, 0.0f, dv, 3,
                         rgb);
  Color c(rgb[0], rgb[1], rgb[2]);
  if (impl_->srgb[index]) c = Color(srgbToLinear(c.r), srgbToLinear(c.g), srgbToLinear(c.b));
  return c;
}

}  // namespace penumbra
