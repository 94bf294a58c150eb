// A linear-RGB float framebuffer. Tiles write disjoint pixels; io encodes it.
#pragma once
#include "core/math.h"
#include <vector>

namespace penumbra {

struct Image {
  int width = 0, height = 0;
  std::vector<Color> pixels;  // row-major, top row first

  Image() = default;
  Image(int w, int h) : width(w), height(h), pixels(static_cast<size_t>(w) * h, Color(0.0f)) {}
  Color& at(int x, int y) { return pixels[static_cast<size_t>(y) * width + x]; }
  const Color& at(int x, int y) const { return pixels[static_cast<size_t>(y) * width + x]; }
};

}  // namespace penumbra
