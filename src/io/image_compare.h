// Error of an image against a reference through OpenImageIO's ImageBufAlgo (image module):
// RMSE and PSNR from ImageBufAlgo::compare, relative MSE from its pixel maths,
// and the RMSE over the worst pixels (penumbra sweep's error figures).
#pragma once
#include "core/error_estimate.h"
#include "core/image.h"

namespace penumbra {

struct ImageError {
  double rmse = 0.0;      // sqrt(mean over pixels and channels of (a - r)^2)
  double relMse = 0.0;    // mean of (a - r)^2 / (r^2 + 0.01), per channel (pbrt's and Mitsuba's relMSE)
  double psnr = 0.0;      // 20 log10(1 / rmse) on values clamped to [0, 1]: display-referred
  double worstRmse = 0.0; // RMSE over the worst 1% of pixels (below)
  double maxError = 0.0;  // largest per-channel difference
  double referenceMean = 0.0;  // the reference's mean over pixels and channels: the
                               // scale "RMSE within x% of the image mean" is read against
  double leftOutShare = 0.0;   // the share of the pixels the figures leave out (leaveOut)
};

// The worst pixels are the 1% (at least one) with the largest squared error summed
// over channels, in this image against the reference: the error where it is
// worst, e.g. a caustic or a shadow edge that the whole-image RMSE averages away.
constexpr double kWorstPixelFraction = 0.01;

// Throws InputError when the sizes differ. `leaveOut` (empty, or one entry per pixel):
// the pixels set there count in none of the figures but referenceMean, e.g. those that
// see an emitter directly, whose aliased edges are the camera's error, not the
// lighting's. With every pixel set, the figures are the whole image's.
ImageError compareImages(const Image& image, const Image& reference, const EmitterMask& leaveOut = {});

}  // namespace penumbra
