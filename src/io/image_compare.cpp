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

ImageError compareImages(const Image& image, const Image& reference) {
  if (image.width != reference.width || image.height != reference.height) {
    throw InputError("reference is " + std::to_string(reference.width) + "x" +
                     std::to_string(reference.height) + ", the image " + std::to_string(image.width) +
                     "x" + std::to_string(image.height));
  }
  ImageError e;
  if (image.pixels.empty()) return e;
  const ImageComparison c = imageCodec().compare(image, reference);
  e.rmse = c.rmse;
  e.maxError = c.maxError;
  e.psnr = c.psnr;
  e.relMse = c.relMse;
  e.referenceMean = c.referenceMean;

  // Worst pixels: squared error summed over channels, the top 1% by nth_element.
  std::vector<double> perPixel(image.pixels.size());
  for (size_t i = 0; i < perPixel.size(); ++i) {
    const Color d = image.pixels[i] - reference.pixels[i];
    perPixel[i] = double(d.r) * d.r + double(d.g) * d.g + double(d.b) * d.b;
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
