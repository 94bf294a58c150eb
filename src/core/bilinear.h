// Bilinear filtering over a texel grid that repeats in u and v (glTF's default
// sampler): the one rule the cut-out masks and the emission maps decoded at load share.
#pragma once
#include "core/math.h"
#include <cmath>

namespace penumbra {

// A texel index in [0, n): floor(coord) mod n, for any finite coordinate.
inline int wrapTexel(float coord, int n) {
  const float m = std::fmod(coord, float(n));
  const int i = static_cast<int>(m < 0.0f ? m + float(n) : m);
  return i >= n || i < 0 ? 0 : i;
}

// Between texel centres at uv (row 0 at the image's top, v = 0); texel(x, y) returns
// the value of one texel (a float or a Color).
template <class TexelAt>
auto bilinearRepeat(int width, int height, Vec2 uv, const TexelAt& texel) {
  const float x = uv.x * float(width) - 0.5f, y = uv.y * float(height) - 0.5f;
  const float fx = std::floor(x), fy = std::floor(y);
  const float tx = x - fx, ty = y - fy;
  const int x0 = wrapTexel(fx, width), y0 = wrapTexel(fy, height);
  const int x1 = x0 + 1 == width ? 0 : x0 + 1, y1 = y0 + 1 == height ? 0 : y0 + 1;
  const auto top = (1.0f - tx) * texel(x0, y0) + tx * texel(x1, y0);
  const auto bottom = (1.0f - tx) * texel(x0, y1) + tx * texel(x1, y1);
  return (1.0f - ty) * top + ty * bottom;
}

}  // namespace penumbra
