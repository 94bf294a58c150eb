// How a texture is read outside [0, 1] and between texels: glTF's sampler (wrapS,
// wrapT, magFilter, minFilter) and the texel index each wrap mode gives.
#pragma once
#include <cmath>
#include <cstdint>

namespace penumbra {

enum class TextureWrap : uint8_t { Repeat, MirroredRepeat, ClampToEdge };
// Between texels when magnified; Auto: the texture system's own smooth filter.
enum class TexelFilter : uint8_t { Auto, Nearest, Linear };
// Across MIP levels when minified; Auto: filtered across levels (anisotropic), None:
// the full-resolution texels only, OneLevel: the nearest level.
enum class MipFilter : uint8_t { Auto, None, OneLevel };

struct TextureSampling {
  TextureWrap wrapS = TextureWrap::Repeat, wrapT = TextureWrap::Repeat;
  TexelFilter texels = TexelFilter::Auto;
  MipFilter mips = MipFilter::Auto;
  bool operator==(const TextureSampling& o) const {
    return wrapS == o.wrapS && wrapT == o.wrapT && texels == o.texels && mips == o.mips;
  }
  bool operator!=(const TextureSampling& o) const { return !(*this == o); }
};

// The texel of a row of n that integer coordinate i (given as a float, so that any
// finite coordinate works) reads. Mirrored repeat repeats the edge texel at each
// turn, as OpenGL's mirror(a) = a >= 0 ? a : -(1 + a) does.
inline int wrapTexel(float i, int n, TextureWrap wrap) {
  if (wrap == TextureWrap::ClampToEdge) return i <= 0.0f ? 0 : i >= float(n - 1) ? n - 1 : int(i);
  const int period = wrap == TextureWrap::Repeat ? n : 2 * n;
  float m = std::fmod(i, float(period));
  if (m < 0.0f) m += float(period);
  int k = int(m);
  if (k < 0 || k >= period) k = 0;  // fmod's rounding at the period's end
  return k < n ? k : period - 1 - k;
}

}  // namespace penumbra
