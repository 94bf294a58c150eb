// A rectangle of a frame's pixels, half-open like pbrt-v4's --pixelbounds:
// [x0, x1) x [y0, y1). The part of a frame one tile renders.
#pragma once
#include <cstddef>

namespace penumbra {

struct PixelBounds {
  int x0 = 0, x1 = 0, y0 = 0, y1 = 0;

  static PixelBounds frame(int width, int height) { return {0, width, 0, height}; }
  int width() const { return x1 - x0; }
  int height() const { return y1 - y0; }
  size_t pixels() const { return empty() ? 0 : static_cast<size_t>(width()) * static_cast<size_t>(height()); }
  bool empty() const { return x1 <= x0 || y1 <= y0; }
  bool contains(int x, int y) const { return x >= x0 && x < x1 && y >= y0 && y < y1; }
  bool covers(int width, int height) const { return x0 <= 0 && y0 <= 0 && x1 >= width && y1 >= height; }
  bool operator==(const PixelBounds& o) const { return x0 == o.x0 && x1 == o.x1 && y0 == o.y0 && y1 == o.y1; }
};

}  // namespace penumbra
