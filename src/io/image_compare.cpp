// ImageBuf views of penumbra images, compared with ImageBufAlgo.
#include "io/image_compare.h"
#include "core/error.h"
#include <OpenImageIO/imagebuf.h>
#include <OpenImageIO/imagebufalgo.h>
#include <algorithm>
#include <cmath>
#include <string>
#include <vector>

namespace penumbra {
namespace {

// Wraps the pixels without copying (Color is three packed floats).
OIIO::ImageBuf view(const Image& image) {
  static_assert(sizeof(Color) == 3 * sizeof(float), "Color must be 3 packed floats");
  OIIO::ImageSpec spec(image.width, image.height, 3, OIIO::TypeDesc::FLOAT);
  return OIIO::ImageBuf(spec, const_cast<Color*>(image.pixels.data()));
}

}  // namespace

ImageError compareImages(const Image& image, const Image& reference) {
  if (image.width != reference.width || image.height != reference.height) {
    throw InputError("reference is " + std::to_string(reference.width) + "x" +
                     std::to_string(reference.height) + ", the image " + std::to_string(image.width) +
                     "x" + std::to_string(image.height));
  }
  ImageError e;
  if (image.pixels.empty()) return e;
  const OIIO::ImageBuf a = view(image), r = view(reference);
  const auto cmp = OIIO::ImageBufAlgo::compare(a, r, 0.0f, 0.0f);
  e.rmse = cmp.rms_error;
  e.maxError = cmp.maxerror;
  // PSNR on display values: the same compare on both clamped to [0, 1].
  const OIIO::ImageBuf ac = OIIO::ImageBufAlgo::clamp(a, 0.0f, 1.0f);
  const OIIO::ImageBuf rc = OIIO::ImageBufAlgo::clamp(r, 0.0f, 1.0f);
  e.psnr = OIIO::ImageBufAlgo::compare(ac, rc, 0.0f, 0.0f).PSNR;

  // relMSE = mean((a - r)^2 / (r^2 + 0.01)), with ImageBufAlgo's per-pixel maths.
  const OIIO::ImageBuf diff = OIIO::ImageBufAlgo::sub(a, r);
  const OIIO::ImageBuf sq = OIIO::ImageBufAlgo::mul(diff, diff);
  const OIIO::ImageBuf den = OIIO::ImageBufAlgo::add(OIIO::ImageBufAlgo::mul(r, r), 0.01f);
  const OIIO::ImageBuf rel = OIIO::ImageBufAlgo::div(sq, den);
  const auto stats = OIIO::ImageBufAlgo::computePixelStats(rel);
  double sum = 0.0;
  for (float v : stats.avg) sum += v;
  e.relMse = sum / static_cast<double>(stats.avg.size());
  double mean = 0.0;
  for (float v : OIIO::ImageBufAlgo::computePixelStats(r).avg) mean += v;
  e.referenceMean = mean / 3.0;

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
