// Adaptive pixel sampling's rule: how many camera samples each pixel takes in the next
// pass, from the per-pixel error of the passes before it (docs/accuracy.md, "Adaptive
// pixel sampling"). A function of earlier passes only: the same for any thread count.
#pragma once
#include "core/image.h"
#include "core/scene.h"
#include <cstdint>
#include <vector>

namespace penumbra {

// The first pass that can take more samples: the per-pixel error needs both sets (an
// even and an odd pass).
inline constexpr int kAdaptiveFirstPass = 2;
// The most samples one pixel may take in a pass (render.adaptive_max_spp's top): each
// has its own random stream below the scrambles' (trace/render.cpp).
inline constexpr int kAdaptiveSppLimit = 1024;

// Its defaults are render.adaptive_threshold's and adaptive_max_spp's (core/scene.h).
struct AdaptiveRule {
  double threshold = 0.0;  // a pixel's standard error over this many times the lighting's noise RMSE
  int spp = 1;             // every pixel's samples a pass
  int maxSpp = 1;          // the most one pixel takes in a pass
};

// Whether the scene's progressive frames sample adaptively: render.adaptive, else its
// model's default (off for classic scenes, whose pixels stay those of uniform sampling).
bool adaptiveSampling(const RenderSettings& render);
// The rule of the scene's render settings.
AdaptiveRule adaptiveRule(const RenderSettings& render, int spp);

// Fills `extra` (one count per pixel) with the samples each pixel takes beyond `spp` in
// the next pass and returns their sum. With u = threshold x imageRmse (the frame's
// lighting noise: pixels that see an emitter would set it by their edges), a pixel whose
// standard error (RMS over its channels) is e > u takes ceil(spp e / u) samples in all,
// at most maxSpp: samples in proportion to a pixel's deviation, the split that
// minimises the mean's squared error for a given number of samples.
uint64_t adaptiveExtras(const Image& standardError, double imageRmse, const AdaptiveRule& rule,
                        std::vector<uint16_t>& extra);

}  // namespace penumbra
