// A linear-RGB float framebuffer, or a geometric view's physical values (depth,
// normals). Tiles write disjoint pixels; io encodes it.
#pragma once
#include "core/math.h"
#include <vector>

namespace penumbra {

// What the pixels mean, so a writer can pick the encoding (io/aov_display.h):
// Depth holds the camera-ray distance in scene units in r = g = b (0 = no hit);
// Normal holds the world-space shading normal in [-1, 1] ((0,0,0) = no hit).
enum class ImageContent { Radiance, Depth, Normal };

struct Image {
  int width = 0, height = 0;
  std::vector<Color> pixels;  // row-major, top row first
  ImageContent content = ImageContent::Radiance;
  // The fraction of a pixel's samples that hit: geometric views, and light over a transparent background; else empty.
  std::vector<float> coverage;

  Image() = default;
  Image(int w, int h) : width(w), height(h), pixels(static_cast<size_t>(w) * h, Color(0.0f)) {}
  Color& at(int x, int y) { return pixels[static_cast<size_t>(y) * width + x]; }
  const Color& at(int x, int y) const { return pixels[static_cast<size_t>(y) * width + x]; }
};

}  // namespace penumbra
