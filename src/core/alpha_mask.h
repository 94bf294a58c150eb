// Cut-out surfaces (glTF alphaMode): the alpha channel decoded at load into plain
// bytes, looked up at a hit's uv by the geometry's intersection filter, and the one
// rule that keeps or drops a hit (a cutoff, or a keyed coin for blended alpha).
#pragma once
#include "core/bilinear.h"
#include "core/math.h"
#include "core/rng.h"
#include <cstdint>
#include <string>
#include <vector>

namespace penumbra {

// Opaque: every hit counts. Mask: a hit counts where alpha >= the cutoff. Blend: a hit
// counts with probability alpha (a stochastic cut-out: the average over rays is the
// blend, and no ray is ever half-stopped).
enum class AlphaMode : uint8_t { Opaque, Mask, Blend };

// One byte of alpha per texel, row 0 at the image's top (v = 0, as textures are looked
// up). Bytes, not floats: a 4k mask is 16 MB, and 8-bit PNG alpha is exact in them.
struct AlphaMask {
  std::string source;  // the image file it came from (materials sharing one share the mask)
  int width = 0, height = 0;
  std::vector<uint8_t> alpha;  // width x height, row after row
  TextureSampling sampling;    // the texture's sampler (repeat in u and v without one)

  // Bilinear between texel centres unless the sampler asks for nearest texels: a
  // magnified mask keeps a smooth cut edge instead of texel-sized steps.
  float at(Vec2 uv) const {
    const auto texel = [&](int x, int y) { return float(alpha[size_t(y) * size_t(width) + size_t(x)]); };
    return sampleTexels(width, height, uv, sampling, texel) * (1.0f / 255.0f);
  }
  size_t bytes() const { return alpha.size(); }
};

// Whether a hit with this coverage counts. `key` identifies the ray and the primitive
// (never the thread), so a blended surface lets the same rays through on any run.
inline bool alphaKeeps(AlphaMode mode, float coverage, float cutoff, uint64_t key) {
  switch (mode) {
    case AlphaMode::Opaque: return true;
    case AlphaMode::Mask: return coverage >= cutoff;
    case AlphaMode::Blend: return float(mix64(key) >> 40) * 0x1p-24f < coverage;
  }
  return true;
}

}  // namespace penumbra
