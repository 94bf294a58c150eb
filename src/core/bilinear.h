// Filtering over a texel grid decoded at load, wrapped as a texture's sampler says:
// the one rule the cut-out masks and the emission maps share.
#pragma once
#include "core/math.h"
#include "core/texture_sampling.h"
#include <cmath>

namespace penumbra {

// The value at uv (row 0 at the image's top, v = 0): the texel under uv when the
// sampler asks for nearest texels, else bilinear between texel centres (any MIP
// filter reads the full-resolution grid). texel(x, y) returns one texel's value (a
// float or a Color).
template <class TexelAt>
auto sampleTexels(int width, int height, Vec2 uv, const TextureSampling& how, const TexelAt& texel) {
  if (how.texels == TexelFilter::Nearest) {
    return texel(wrapTexel(std::floor(uv.x * float(width)), width, how.wrapS),
                 wrapTexel(std::floor(uv.y * float(height)), height, how.wrapT));
  }
  const float x = uv.x * float(width) - 0.5f, y = uv.y * float(height) - 0.5f;
  const float fx = std::floor(x), fy = std::floor(y);
  const float tx = x - fx, ty = y - fy;
  const int x0 = wrapTexel(fx, width, how.wrapS), y0 = wrapTexel(fy, height, how.wrapT);
  const int x1 = wrapTexel(fx + 1.0f, width, how.wrapS), y1 = wrapTexel(fy + 1.0f, height, how.wrapT);
  const auto top = (1.0f - tx) * texel(x0, y0) + tx * texel(x1, y0);
  const auto bottom = (1.0f - tx) * texel(x0, y1) + tx * texel(x1, y1);
  return (1.0f - ty) * top + ty * bottom;
}

}  // namespace penumbra
