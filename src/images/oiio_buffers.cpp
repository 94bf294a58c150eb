// The image module's whole-image work on OpenImageIO's ImageBuf: an image read as
// linear RGB, an emissive texture reduced for lighting, error figures against a
// reference, and a sweep's contact sheet drawn with labels.
#include "core/color.h"
#include "core/emission_map.h"
#include "core/error.h"
#include "images/oiio_parts.h"

#include <OpenImageIO/imagebuf.h>
#include <OpenImageIO/imagebufalgo.h>
#include <OpenImageIO/strutil.h>

#include <algorithm>
#include <cmath>
#include <filesystem>

namespace penumbra::oiio {

std::string readLinear(const std::string& path, Image& image) {
  // Keep colour unassociated: alpha is dropped, so premultiplying would darken.
  OIIO::ImageSpec config;
  config.attribute("oiio:UnassociatedAlpha", 1);
  OIIO::ImageBuf buf(path, 0, 0, nullptr, &config);
  if (!buf.read(0, 0, /*force=*/true, OIIO::TypeDesc::FLOAT)) return failed(buf.geterror());
  // nativespec: the file's own format and attributes, not the float buffer's.
  const OIIO::ImageSpec& spec = buf.nativespec();
  const int channels = spec.nchannels;
  if (spec.width <= 0 || spec.height <= 0 || channels <= 0) return "no pixels";

  // How the stored values relate to linear light. Integer files that say
  // nothing are taken as sRGB, which is what 8-bit images almost always are.
  std::string colorSpace = spec.get_string_attribute("oiio:ColorSpace");
  bool srgb = isSrgbEncoded(colorSpace, integerType(spec.format));
  float gamma = OIIO::Strutil::istarts_with(colorSpace, "Gamma")
                    ? spec.get_float_attribute("oiio:Gamma", 2.2f)
                    : 1.0f;

  std::vector<float> data(static_cast<size_t>(spec.width) * spec.height * channels);
  OIIO::ROI roi = buf.roi();
  if (!buf.get_pixels(roi, OIIO::TypeDesc::FLOAT, data.data())) return failed(buf.geterror());

  auto linearise = [&](float v) {
    if (!std::isfinite(v)) return 0.0f;
    if (srgb) return static_cast<float>(srgbDecode(v));
    if (gamma != 1.0f) return std::pow(std::max(v, 0.0f), gamma);
    return v;
  };
  // Grey (and grey + alpha) is replicated; anything past RGB, alpha included, is dropped.
  const bool grey = channels < 3;
  image = Image(spec.width, spec.height);
  for (size_t i = 0; i < image.pixels.size(); ++i) {
    const float* p = &data[i * channels];
    for (int c = 0; c < 3; ++c) image.pixels[i][c] = linearise(p[grey ? 0 : c]);
  }
  return "";
}

// Channels to RGB, sRGB to linear before any averaging, then ImageBufAlgo's resize.
EmissionMap readEmissionMap(const std::string& path, const UvTransform& transform, int maxSide) {
  auto fail = [&](const std::string& why) { throw InputError(path + ": cannot read emissive texture: " + why); };
  OIIO::ImageBuf source(path);
  if (!source.read(0, 0, true, OIIO::TypeDesc::FLOAT)) fail(source.geterror());
  const OIIO::ImageSpec& spec = source.spec();
  const bool srgb = isSrgbEncoded(source.nativespec().get_string_attribute("oiio:ColorSpace"),
                                  integerType(source.nativespec().format));
  // RGB, or the grey channel three times (texture lookups read grey the same way).
  const int order[3] = {0, spec.nchannels >= 3 ? 1 : 0, spec.nchannels >= 3 ? 2 : 0};
  OIIO::ImageBuf rgb = OIIO::ImageBufAlgo::channels(source, 3, order);
  if (rgb.has_error()) fail(rgb.geterror());
  if (srgb) {
    for (OIIO::ImageBuf::Iterator<float> it(rgb); !it.done(); ++it) {
      for (int c = 0; c < 3; ++c) it[c] = float(srgbDecode(it[c]));
    }
  }
  const int largest = std::max(spec.width, spec.height);
  if (largest > maxSide) {
    const int w = std::max(1, spec.width * maxSide / largest);
    const int h = std::max(1, spec.height * maxSide / largest);
    rgb = OIIO::ImageBufAlgo::resize(rgb, "box", 0.0f, OIIO::ROI(0, w, 0, h, 0, 1, 0, 3));
    if (rgb.has_error()) fail(rgb.geterror());
  }
  EmissionMap map;
  map.width = rgb.spec().width;
  map.height = rgb.spec().height;
  map.transform = transform;
  map.texels.resize(size_t(map.width) * size_t(map.height));
  if (!rgb.get_pixels(OIIO::ROI(0, map.width, 0, map.height, 0, 1, 0, 3), OIIO::TypeDesc::FLOAT, map.texels.data())) {
    fail(rgb.geterror());
  }
  return map;
}

namespace {

// Wraps the pixels without copying (Color is three packed floats).
OIIO::ImageBuf view(const Image& image) {
  static_assert(sizeof(Color) == 3 * sizeof(float), "Color must be 3 packed floats");
  OIIO::ImageSpec spec(image.width, image.height, 3, OIIO::TypeDesc::FLOAT);
  return OIIO::ImageBuf(spec, const_cast<Color*>(image.pixels.data()));
}

}  // namespace

ImageComparison compare(const Image& image, const Image& reference) {
  ImageComparison e;
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
  return e;
}

namespace {

constexpr int kTileWidth = 192, kColumns = 8, kLabelHeight = 34, kGap = 6, kFontSize = 12;
constexpr const char* kFont = "/usr/share/fonts/truetype/dejavu/DejaVuSans.ttf";

}  // namespace

// Each image resized in linear light, pasted into one linear canvas, labelled with
// render_text in DejaVu Sans (Debian's fonts-dejavu-core, which make deps installs).
std::string drawContactSheet(const std::vector<std::string>& images,
                             const std::vector<std::vector<std::string>>& labels, Image& out) {
  if (!std::filesystem::exists(kFont)) return "no font for its labels (make deps installs fonts-dejavu-core)";
  std::vector<OIIO::ImageBuf> thumbs;
  int tileHeight = 1;
  for (const std::string& image : images) {
    OIIO::ImageBuf in(image);
    if (!in.read(0, 0, 0, 3, true, OIIO::TypeDesc::FLOAT)) return "cannot read " + image;
    const OIIO::ImageSpec& spec = in.spec();
    const int h = std::max(1, int(std::lround(double(kTileWidth) * spec.height / std::max(1, spec.width))));
    thumbs.push_back(OIIO::ImageBufAlgo::resize(in, "", 0.0f, OIIO::ROI(0, kTileWidth, 0, h, 0, 1, 0, 3)));
    tileHeight = std::max(tileHeight, h);
  }
  const int columns = std::min<int>(kColumns, int(images.size()));
  const int rows = int((images.size() + size_t(columns) - 1) / size_t(columns));
  const int cellW = kTileWidth + kGap, cellH = tileHeight + kLabelHeight + kGap;
  OIIO::ImageBuf sheet(OIIO::ImageSpec(columns * cellW + kGap, rows * cellH + kGap, 3, OIIO::TypeDesc::FLOAT));
  OIIO::ImageBufAlgo::fill(sheet, {0.02f, 0.02f, 0.02f});
  const float white[] = {1.0f, 1.0f, 1.0f};
  for (size_t i = 0; i < images.size(); ++i) {
    const int x = kGap + int(i % size_t(columns)) * cellW, y = kGap + int(i / size_t(columns)) * cellH;
    OIIO::ImageBufAlgo::paste(sheet, x, y, 0, 0, thumbs[i]);
    for (size_t l = 0; l < labels[i].size() && l < 2; ++l) {
      const int baseline = y + tileHeight + kFontSize + 2 + int(l) * (kFontSize + 3);
      if (!OIIO::ImageBufAlgo::render_text(sheet, x, baseline, labels[i][l], kFontSize, kFont, white)) {
        return "cannot draw its labels: " + sheet.geterror();
      }
    }
  }
  out = Image(sheet.spec().width, sheet.spec().height);
  sheet.get_pixels(OIIO::ROI(0, out.width, 0, out.height, 0, 1, 0, 3), OIIO::TypeDesc::FLOAT, out.pixels.data());
  return "";
}

}  // namespace penumbra::oiio
