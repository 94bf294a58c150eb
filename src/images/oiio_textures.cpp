// The image module's textures: OpenImageIO's TextureSystem, one handle per texture,
// sRGB-encoded files linearised after filtering.
#include "core/color.h"
#include "core/error.h"
#include "images/oiio_parts.h"

#include <OpenImageIO/texture.h>

#include <algorithm>

namespace penumbra::oiio {
namespace {

// OpenImageIO's wrap modes work on texel indices as OpenGL's do: its mirror repeats
// the edge texel at each turn, its clamp reads the edge texel.
OIIO::TextureOpt::Wrap wrapMode(TextureWrap wrap) {
  switch (wrap) {
    case TextureWrap::Repeat: return OIIO::TextureOpt::WrapPeriodic;
    case TextureWrap::MirroredRepeat: return OIIO::TextureOpt::WrapMirror;
    case TextureWrap::ClampToEdge: return OIIO::TextureOpt::WrapClamp;
  }
  return OIIO::TextureOpt::WrapPeriodic;
}

class Sampler final : public TextureSampler {
 public:
  Sampler(const std::vector<std::string>& paths, const std::vector<bool>& data)
      : system_(OIIO::TextureSystem::create(false)) {
    // Files written without MIP levels still get them, built once in the cache.
    system_->attribute("automip", 1);
    system_->attribute("max_memory_MB", 1024.0f);
    for (size_t i = 0; i < paths.size(); ++i) {
      const std::string& path = paths[i];
      OIIO::ImageSpec spec;
      if (!system_->get_imagespec(OIIO::ustring(path), 0, spec)) {
        std::string err = system_->geterror();
        std::replace(err.begin(), err.end(), '\n', ' ');
        while (!err.empty() && err.back() == ' ') err.pop_back();
        OIIO::TextureSystem::destroy(system_);
        throw InputError(path + ": cannot read texture: " + err);
      }
      entries_.push_back({system_->get_texture_handle(OIIO::ustring(path)), spec.nchannels >= 3 ? 3 : 1,
                          !(i < data.size() && data[i]) &&
                              isSrgbEncoded(spec.get_string_attribute("oiio:ColorSpace"), integerType(spec.format))});
    }
  }
  ~Sampler() override { OIIO::TextureSystem::destroy(system_); }

  Color sample(int index, float s, float t, float ds, float dt, const TextureSampling& how) const override {
    const Entry& e = entries_[size_t(index)];
    OIIO::TextureOpt opt;
    opt.swrap = wrapMode(how.wrapS);
    opt.twrap = wrapMode(how.wrapT);
    // Auto keeps the library's own choices (smart bicubic, anisotropic MIP filter).
    if (how.texels != TexelFilter::Auto) {
      opt.interpmode = how.texels == TexelFilter::Nearest ? OIIO::TextureOpt::InterpClosest
                                                          : OIIO::TextureOpt::InterpBilinear;
    }
    if (how.mips == MipFilter::None) opt.mipmode = OIIO::TextureOpt::MipModeNoMIP;
    if (how.mips == MipFilter::OneLevel) opt.mipmode = OIIO::TextureOpt::MipModeOneLevel;
    float v[3] = {1.0f, 0.0f, 1.0f};
    auto* perthread = system_->get_perthread_info();
    system_->texture(e.handle, perthread, opt, s, t, ds, 0.0f, 0.0f, dt, e.channels, v);
    Color c = e.channels == 3 ? Color(v[0], v[1], v[2]) : Color(v[0]);
    // Filtering happens on the stored (encoded) values; decoding afterwards is the
    // usual approximation and exact wherever the footprint covers one texel.
    return e.srgb ? srgbToLinear(c) : c;
  }

 private:
  struct Entry {
    OIIO::TextureSystem::TextureHandle* handle;
    int channels;  // 1 (grey, replicated) or 3; grey+alpha reads only the grey channel
    bool srgb;     // stored values are sRGB-encoded: linearise after filtering
  };
  OIIO::TextureSystem* system_;
  std::vector<Entry> entries_;
};

}  // namespace

std::unique_ptr<TextureSampler> textures(const std::vector<std::string>& paths, const std::vector<bool>& data) {
  return std::make_unique<Sampler>(paths, data);
}

}  // namespace penumbra::oiio
