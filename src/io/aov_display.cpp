// Depth normalisation and the normal colour map for display. They are the
// visualisation earlier versions rendered directly, so old PNGs keep their bytes.
#include "io/aov_display.h"
#include <algorithm>
#include <cmath>
#include <limits>

namespace penumbra {
namespace {

// A pixel hit something if any sample did; without coverage, depth 0 means no hit
// (a hit is always a positive distance along the ray).
bool hitAt(const Image& image, size_t i) {
  return image.coverage.empty() ? image.pixels[i].r > 0.0f : image.coverage[i] > 0.0f;
}

// Near black, far white, misses white; a flat image (one distance) is black.
Image depthDisplay(const Image& depth) {
  Image out(depth.width, depth.height);
  constexpr float inf = std::numeric_limits<float>::infinity();
  float lo = inf, hi = -inf;
  for (size_t i = 0; i < depth.pixels.size(); ++i) {
    if (hitAt(depth, i)) { lo = std::min(lo, depth.pixels[i].r); hi = std::max(hi, depth.pixels[i].r); }
  }
  const float range = hi > lo ? hi - lo : 1.0f;
  for (size_t i = 0; i < depth.pixels.size(); ++i) {
    out.pixels[i] = hitAt(depth, i) ? Color((depth.pixels[i].r - lo) / range) : Color(1.0f);
  }
  return out;
}

// In double, then rounded once: for one sample per pixel (coverage 1 or 0) this is
// exactly the float n * 0.5f + 0.5f the renderer used to store.
Image normalDisplay(const Image& normal) {
  Image out(normal.width, normal.height);
  for (size_t i = 0; i < normal.pixels.size(); ++i) {
    const double cover = normal.coverage.empty() ? 1.0 : normal.coverage[i];
    if (!(cover > 0.0)) continue;  // black
    for (int c = 0; c < 3; ++c) out.pixels[i][c] = static_cast<float>(cover * (normal.pixels[i][c] * 0.5 + 0.5));
  }
  return out;
}

}  // namespace

Image aovDisplay(const Image& image) {
  switch (image.content) {
    case ImageContent::Depth: return depthDisplay(image);
    case ImageContent::Normal: return normalDisplay(image);
    default: return image;
  }
}

}  // namespace penumbra
