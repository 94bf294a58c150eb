// Error figures of an image against a reference: the image module's ImageBufAlgo
// maths for RMSE, PSNR and relative MSE, and the worst pixels here.
#include "io/image_compare.h"
#include "core/error.h"
#include "core/image_codec.h"
#include <algorithm>
#include <cmath>
#include <string>
#include <vector>

namespace penumbra {

ImageError compareImages(const Image& image, const Image& reference, const EmitterMask& leaveOut) {
  if (image.width != reference.width || image.height != reference.height) {
    throw InputError("reference is " + std::to_string(reference.width) + "x" +
                     std::to_string(reference.height) + ", the image " + std::to_string(image.width) +
                     "x" + std::to_string(image.height));
  }
  ImageError e;
  if (image.pixels.empty()) return e;
  bool masked = leaveOut.size() == image.pixels.size();
  size_t kept = image.pixels.size();
  if (masked) kept -= size_t(std::count_if(leaveOut.begin(), leaveOut.end(), [](uint8_t m) { return m != 0; }));
  // Every pixel left out: the whole image's figures, not a perfect zero.
  if (kept == 0) masked = false, kept = image.pixels.size();
  e.leftOutShare = 1.0 - double(kept) / double(image.pixels.size());
  // A left-out pixel takes the reference's value, so it adds nothing to the sums; the
  // means are then over the pixels kept.
  Image compared;
  if (masked && kept < image.pixels.size()) {
    compared = image;
    for (size_t i = 0; i < leaveOut.size(); ++i) {
      if (leaveOut[i]) compared.pixels[i] = reference.pixels[i];
    }
  }
  const Image& a = compared.pixels.empty() ? image : compared;
  const ImageComparison c = imageCodec().compare(a, reference);
  const double scale = double(image.pixels.size()) / double(kept);
  e.rmse = c.rmse * std::sqrt(scale);
  e.maxError = c.maxError;
  e.psnr = c.psnr - 10.0 * std::log10(scale);
  e.relMse = c.relMse * scale;
  e.referenceMean = c.referenceMean;

  // Worst pixels: squared error summed over channels, the top 1% by nth_element.
  std::vector<double> perPixel;
  perPixel.reserve(kept);
  for (size_t i = 0; i < image.pixels.size(); ++i) {
    if (masked && leaveOut[i]) continue;
    const Color d = image.pixels[i] - reference.pixels[i];
    perPixel.push_back(double(d.r) * d.r + double(d.g) * d.g + double(d.b) * d.b);
  }
  const size_t worst = std::max<size_t>(1, static_cast<size_t>(perPixel.size() * kWorstPixelFraction));
  std::nth_element(perPixel.begin(), perPixel.begin() + (worst - 1), perPixel.end(),
                   [](double x, double y) { return x > y; });
  double tail = 0.0;
  for (size_t i = 0; i < worst; ++i) tail += perPixel[i];
  e.worstRmse = std::sqrt(tail / (3.0 * worst));
  return e;
}

}  // namespace penumbra
