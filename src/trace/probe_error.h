// The error of an image of one sample per pixel, which has no spread of its own: its
// pixel centres against the pixels they stand for, measured by probes.
#pragma once
#include "core/error_estimate.h"
#include "core/image.h"
#include "core/pixel_bounds.h"
#include "core/view.h"
#include "trace/shading.h"

namespace penumbra {

// Probed pixels asked for: a 256th of the image, at least 512. Pixels are picked
// with a chance that follows their contrast with their neighbours, where the centre
// sample's error lives (edges, highlights), so the probed ones are fewer than asked
// where many pixels are certain to be picked.
constexpr double kProbeShare = 1.0 / 256.0;
constexpr int kMinProbes = 512;

// Each probed pixel takes two independent jittered grids of samples (2x2 each, 4x4
// where it is certain to be picked: the brightest edges), whose means A and B make
// (X - A)(X - B) an unbiased estimate of the centre X's squared error; each is weighed
// by the inverse of the pixel's chance. The image's figure is the root of their mean
// over pixels and channels (ErrorSource::Probes, count = pixels probed). Shading
// noise is in it; the photon map's is not (the probes read the same maps). With
// `perPixel`, every pixel is probed and gets sqrt(max(0, estimate)) per channel
// (the error view). Deterministic for any thread count; the probes' rays are not
// counted in the render's. `bounds`: a part of the frame, probed as if it were the
// whole image (its own contrast, picks and mean); null: the whole image.
ErrorEstimate probeError(const ShadingContext& ctx, const Image& image, Aov aov, Image* perPixel = nullptr,
                         const PixelBounds* bounds = nullptr);

}  // namespace penumbra
