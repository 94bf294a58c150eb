// The tile-parallel image loop: camera rays, stratified samples per pixel, and
// the depth/normal/indirect views (depth and normal as physical values, with
// their coverage; views of light with theirs over a transparent background).
// Deterministic for any thread count.
#pragma once
#include "core/image.h"
#include "core/pixel_bounds.h"
#include "core/progress.h"
#include "core/ray_record.h"
#include "core/view.h"
#include "trace/shading.h"
#include <functional>
#include <optional>
#include <string>
#include <vector>

namespace penumbra {

struct RenderOptions {
  Aov aov = Aov::Beauty;
  int tileSize = 16;
  // Expects every tile, then adds one per tile done (a relaxed atomic add); null: none.
  ProgressCounter* tiles = nullptr;
  // Filled per pixel with the standard error of its mean, from its even and odd
  // samples' means (0 below two samples); null: not kept. The root, not the variance:
  // a variance of finite pixels (1e20 squared) can overflow float, their error cannot.
  Image* standardError = nullptr;
  // Filled per pixel with the mean over its samples of their gathers' smoothing bias
  // (ThreadState::smoothing), when the context's gathers probe it; null: not kept.
  Image* smoothing = nullptr;
  // Set: only these pixels are rendered (a tile of the frame); the others stay 0. Each
  // pixel's samples and packets are the whole frame's, so its value is too.
  std::optional<PixelBounds> bounds;
  // Set (adaptive sampling, core/adaptive_sampling.h): pixel i takes extra[i] samples
  // after its spp, from streams and a sequence of this pass's own; null: none.
  const std::vector<uint16_t>* extra = nullptr;
};

// One sample of view `aov` along a camera ray, its first hit traced here (the caller
// has begun the sample: beginSample).
Color shadeCameraRay(const ShadingContext& ctx, const Ray& ray, Aov aov, ThreadState& ts);

// Renders the image (or its bounds, at full size); `counts` receives the sum of every thread's counters.
Image renderImage(const ShadingContext& ctx, const RenderOptions& options, RayCounts& counts);

// Throws InputError unless (x, y) is a pixel of the camera's image.
void checkPixel(const Camera& camera, int x, int y);

// The full ray tree of one pixel's first sample (--trace-pixel).
RayTree tracePixel(const ShadingContext& ctx, int x, int y);

}  // namespace penumbra
