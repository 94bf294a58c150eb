// Image file I/O through OpenImageIO: the sRGB transfer curve, the choice of
// writer by extension, encoding in memory for the checked write-and-rename that
// keeps targets whole, and the cheap test that a file on disk is whole.
#include "io/image_io.h"
#include "core/color.h"

#include "core/error.h"
#include "io/aov_display.h"
#include "io/image_encode.h"
#include "io/temp_file.h"

#include <OpenImageIO/filesystem.h>
#include <OpenImageIO/imagebuf.h>
#include <OpenImageIO/imageio.h>
#include <OpenImageIO/strutil.h>

#include <fcntl.h>
#include <sys/stat.h>
#include <unistd.h>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <cstring>
#include <filesystem>
#include <limits>
#include <stdexcept>
#include <system_error>

namespace penumbra {
namespace {

namespace fs = std::filesystem;

enum class Encoding { Srgb8, Exr };

// NaN never gets here (writeImage refuses it); +Inf is the brightest value there
// is, so it saturates to white like any other value above 1, and -Inf to black.
uint8_t toSrgb8(float linear) {
  if (!(linear > 0.0f)) return 0;
  if (linear >= 1.0f) return 255;
  return static_cast<uint8_t>(std::floor(srgbEncode(linear) * 255.0 + 0.5));
}

// Largest finite half: anything brighter (+Inf included) would become +Inf in the
// EXR, so it clamps there; radiance is never negative, so -Inf and negatives are 0.
constexpr float kHalfMax = 65504.0f;
float toHalfSafe(float linear) {
  if (!(linear > 0.0f)) return 0.0f;
  return std::min(linear, kHalfMax);
}

// Depth and normals are measurements, not light: kept in 32-bit float (half's 11
// bits would round a 10 m depth to 8 mm) with their sign, finite (no +-Inf either).
float toFloatFinite(float value) {
  constexpr float top = std::numeric_limits<float>::max();
  return std::clamp(value, -top, top);
}

bool geometric(const Image& image) { return image.content != ImageContent::Radiance; }

// One EXR layer: its channel-name prefix ("" for a plain RGB file) and its image.
struct ExrLayer {
  std::string name;
  const Image* image;
};

// The EXR header and interleaved pixels of `layers`: R, G, B per layer (half for
// radiance, float for geometric views) and, for a geometric view, A = its coverage.
OIIO::ImageSpec exrSpec(const std::vector<ExrLayer>& layers, std::vector<float>& floats) {
  std::vector<std::string> names;
  std::vector<OIIO::TypeDesc> formats;
  bool anyFloat = false;
  for (const ExrLayer& l : layers) {
    const std::string prefix = l.name.empty() ? "" : l.name + ".";
    const bool exact = geometric(*l.image);
    anyFloat = anyFloat || exact;
    for (const char* c : {"R", "G", "B", "A"}) {
      if (*c == 'A' && l.image->coverage.empty()) continue;
      names.push_back(prefix + c);
      formats.push_back(exact ? OIIO::TypeDesc::FLOAT : OIIO::TypeDesc::HALF);
    }
  }
  const Image& first = *layers.front().image;
  const size_t n = names.size();
  OIIO::ImageSpec spec(first.width, first.height, static_cast<int>(n), anyFloat ? OIIO::TypeDesc::FLOAT
                                                                                : OIIO::TypeDesc::HALF);
  // Only what differs from the default, so a radiance EXR keeps its old header.
  if (!layers.front().name.empty()) spec.channelnames = names;
  if (anyFloat && std::any_of(formats.begin(), formats.end(), [](auto f) { return f != OIIO::TypeDesc::FLOAT; }))
    spec.channelformats = formats;
  if (layers.size() == 1 && n == 4) spec.alpha_channel = 3;
  floats.resize(first.pixels.size() * n);
  for (size_t i = 0; i < first.pixels.size(); ++i) {
    float* out = &floats[i * n];
    for (const ExrLayer& l : layers) {
      const Image& im = *l.image;
      for (int c = 0; c < 3; ++c) *out++ = geometric(im) ? toFloatFinite(im.pixels[i][c]) : toHalfSafe(im.pixels[i][c]);
      if (!im.coverage.empty()) *out++ = im.coverage[i];
    }
  }
  return spec;
}

// The render drops non-finite samples, so a NaN here is a bug upstream: say where,
// rather than write a pixel that silently looks black.
void refuseNan(const std::string& path, const Image& image) {
  for (size_t i = 0; i < image.pixels.size(); ++i) {
    const Color& c = image.pixels[i];
    if (std::isnan(c.r) || std::isnan(c.g) || std::isnan(c.b)) {
      throw std::logic_error(path + ": image has a NaN at pixel (" + std::to_string(i % image.width) +
                             ", " + std::to_string(i / image.width) + "); nothing was written");
    }
  }
}

// OIIO error strings can span lines; InputError messages are one line.
std::string oneLine(std::string text) {
  std::replace(text.begin(), text.end(), '\n', ' ');
  text = OIIO::Strutil::strip(text);
  return text.empty() ? "unknown error" : text;
}

[[noreturn]] void writeFailed(const std::string& path, const std::string& reason) {
  throw InputError(path + ": cannot write image: " + oneLine(reason));
}

}  // namespace

// Encodes the image in memory (the writer chosen by the target's extension), then
// writes the bytes through the one checked write-and-rename (temp_file.h): OIIO's
// PNG writer does not report a short write, so it never touches the disk itself.
void writeAtomically(const std::string& path, const OIIO::ImageSpec& spec, OIIO::TypeDesc pixelType,
                     const void* pixels) {
  auto out = OIIO::ImageOutput::create(path);
  if (!out) writeFailed(path, OIIO::geterror());
  if (!out->supports("ioproxy")) writeFailed(path, std::string(out->format_name()) + " cannot be encoded in memory");
  // Room for the file uncompressed (zip's worst case adds < 1/64), so the buffer never
  // grows by copying; pages it leaves untouched cost no memory.
  std::vector<unsigned char> bytes;
  const size_t raw = spec.image_bytes(/*native=*/true);
  bytes.reserve(raw + raw / 64 + 65536);
  OIIO::Filesystem::IOVecOutput proxy(bytes);
  if (!out->set_ioproxy(&proxy) || !out->open(path, spec)) writeFailed(path, out->geterror());
  if (!out->write_image(pixelType, pixels)) {
    const std::string reason = out->geterror();
    out->close();
    writeFailed(path, reason);
  }
  if (!out->close()) writeFailed(path, out->geterror());
  out.reset();  // the writer may still hold the proxy until it is destroyed
  writeFileAtomic(path, bytes.data(), bytes.size(), "image");
}

namespace {

// A PNG's last chunk: length 0, "IEND", its CRC.
constexpr unsigned char kPngEnd[12] = {0, 0, 0, 0, 'I', 'E', 'N', 'D', 0xAE, 0x42, 0x60, 0x82};

bool pngEndsWhole(const std::string& path) {
  const int fd = ::open(path.c_str(), O_RDONLY | O_CLOEXEC);
  if (fd < 0) return false;
  struct stat st;
  unsigned char tail[sizeof kPngEnd];
  const bool ok = ::fstat(fd, &st) == 0 && st.st_size >= static_cast<off_t>(8 + sizeof tail) &&
                  ::pread(fd, tail, sizeof tail, st.st_size - static_cast<off_t>(sizeof tail)) ==
                      static_cast<ssize_t>(sizeof tail) &&
                  std::memcmp(tail, kPngEnd, sizeof tail) == 0;
  ::close(fd);
  return ok;
}

}  // namespace

void checkImageOutputPath(const std::string& path) {
  fs::path target(path);
  std::string ext = OIIO::Strutil::lower(target.extension().string());
  if (ext != ".png" && ext != ".exr") {
    throw InputError(path + ": unsupported image extension '" + target.extension().string() +
                     "' (use .png or .exr)");
  }
  const std::string problem = outputPathProblem(path);
  if (!problem.empty()) writeFailed(path, problem);
}

void writeImage(const std::string& path, const Image& image, const ImageMetadata& metadata,
                const DisplayOptions& display) {
  checkImageOutputPath(path);
  fs::path target(path);
  Encoding encoding = OIIO::Strutil::lower(target.extension().string()) == ".png" ? Encoding::Srgb8
                                                                                  : Encoding::Exr;
  if (image.width <= 0 || image.height <= 0 ||
      image.pixels.size() != static_cast<size_t>(image.width) * image.height ||
      (!image.coverage.empty() && image.coverage.size() != image.pixels.size())) {
    writeFailed(path, "image is empty or its pixel count does not match its size");
  }
  refuseNan(path, image);

  std::vector<uint8_t> bytes;
  std::vector<float> floats;
  OIIO::ImageSpec spec;
  const void* pixels = nullptr;
  OIIO::TypeDesc pixelType;
  if (encoding == Encoding::Srgb8) {
    const Image shown = aovDisplay(image);  // depth and normals as pictures; radiance as is
    const size_t count = shown.pixels.size() * 3;
    spec = OIIO::ImageSpec(image.width, image.height, 3, OIIO::TypeDesc::UINT8);
    spec.attribute("oiio:ColorSpace", "sRGB");
    // Only when asked for: a default PNG keeps today's bytes, metadata included.
    if (display.tone != ToneMap::Clamp || display.exposure != 0.0f) {
      spec.attribute("penumbra:tonemap", toneMapName(display.tone));
      spec.attribute("penumbra:exposure", display.exposure);
    }
    bytes.resize(count);
    for (size_t i = 0; i < shown.pixels.size(); ++i)
      for (int c = 0; c < 3; ++c) bytes[i * 3 + c] = toSrgb8(displayValue(shown.pixels[i][c], display));
    pixels = bytes.data();
    pixelType = OIIO::TypeDesc::UINT8;
  } else {
    spec = exrSpec({{"", &image}}, floats);
    spec.attribute("oiio:ColorSpace", "Linear");
    pixels = floats.data();
    pixelType = OIIO::TypeDesc::FLOAT;  // OIIO converts to the file's half
  }
  spec.attribute("Software", "penumbra");
  for (const auto& [key, value] : metadata) spec.attribute(key, value);

  writeAtomically(path, spec, pixelType, pixels);
}

void writeLayeredExr(const std::string& path, const std::vector<std::pair<std::string, Image>>& layers,
                     const ImageMetadata& metadata) {
  checkImageOutputPath(path);
  if (layers.empty()) writeFailed(path, "no layers");
  const Image& first = layers.front().second;
  std::vector<ExrLayer> parts;
  for (const auto& [name, image] : layers) {
    if (image.width != first.width || image.height != first.height || image.pixels.empty() ||
        (!image.coverage.empty() && image.coverage.size() != image.pixels.size())) {
      writeFailed(path, "layer '" + name + "' is empty or not the size of the others");
    }
    refuseNan(path, image);
    parts.push_back({name, &image});
  }
  std::vector<float> floats;
  OIIO::ImageSpec spec = exrSpec(parts, floats);
  spec.attribute("oiio:ColorSpace", "Linear");
  spec.attribute("Software", "penumbra");
  for (const auto& [key, value] : metadata) spec.attribute(key, value);
  writeAtomically(path, spec, OIIO::TypeDesc::FLOAT, floats.data());
}

bool imageComplete(const std::string& path) {
  if (OIIO::Strutil::iends_with(path, ".png")) return pngEndsWhole(path);
  // EXR and the rest: the header opens and the last scanline (its chunk is the
  // file's last, or past a truncated file's end) decodes.
  auto in = OIIO::ImageInput::open(path);
  if (!in) {
    (void)OIIO::geterror();
    return false;
  }
  const OIIO::ImageSpec& spec = in->spec();
  std::vector<float> row(static_cast<size_t>(std::max(spec.width, 0)) * std::max(spec.nchannels, 0));
  const bool ok = !row.empty() && in->read_scanlines(0, 0, spec.y + spec.height - 1, spec.y + spec.height, 0, 0,
                                                     spec.nchannels, OIIO::TypeDesc::FLOAT, row.data());
  (void)in->geterror();
  in->close();
  return ok;
}

std::string readImageAttribute(const std::string& path, const std::string& name) {
  auto in = OIIO::ImageInput::open(path);
  if (!in) {
    (void)OIIO::geterror();  // clear OIIO's pending error: a missing file is a plain answer here
    return "";
  }
  const std::string value = in->spec().get_string_attribute(name);
  in->close();
  return value;
}

Image readImage(const std::string& path) {
  // Keep colour unassociated: alpha is dropped, so premultiplying would darken.
  OIIO::ImageSpec config;
  config.attribute("oiio:UnassociatedAlpha", 1);
  OIIO::ImageBuf buf(path, 0, 0, nullptr, &config);
  if (!buf.read(0, 0, /*force=*/true, OIIO::TypeDesc::FLOAT)) {
    throw InputError(path + ": cannot read image: " + oneLine(buf.geterror()));
  }
  // nativespec: the file's own format and attributes, not the float buffer's.
  const OIIO::ImageSpec& spec = buf.nativespec();
  const int channels = spec.nchannels;
  if (spec.width <= 0 || spec.height <= 0 || channels <= 0) {
    throw InputError(path + ": cannot read image: no pixels");
  }

  // How the stored values relate to linear light. Integer files that say
  // nothing are taken as sRGB, which is what 8-bit images almost always are.
  std::string colorSpace = spec.get_string_attribute("oiio:ColorSpace");
  bool integer = spec.format.basetype != OIIO::TypeDesc::FLOAT &&
                 spec.format.basetype != OIIO::TypeDesc::HALF &&
                 spec.format.basetype != OIIO::TypeDesc::DOUBLE;
  bool srgb = isSrgbEncoded(colorSpace, integer);
  float gamma = OIIO::Strutil::istarts_with(colorSpace, "Gamma")
                    ? spec.get_float_attribute("oiio:Gamma", 2.2f)
                    : 1.0f;

  std::vector<float> data(static_cast<size_t>(spec.width) * spec.height * channels);
  OIIO::ROI roi = buf.roi();
  if (!buf.get_pixels(roi, OIIO::TypeDesc::FLOAT, data.data())) {
    throw InputError(path + ": cannot read image: " + oneLine(buf.geterror()));
  }

  auto linearise = [&](float v) {
    if (!std::isfinite(v)) return 0.0f;
    if (srgb) return static_cast<float>(srgbDecode(v));
    if (gamma != 1.0f) return std::pow(std::max(v, 0.0f), gamma);
    return v;
  };
  // Grey (and grey + alpha) is replicated; anything past RGB, alpha included, is dropped.
  const bool grey = channels < 3;
  Image image(spec.width, spec.height);
  for (size_t i = 0; i < image.pixels.size(); ++i) {
    const float* p = &data[i * channels];
    for (int c = 0; c < 3; ++c) image.pixels[i][c] = linearise(p[grey ? 0 : c]);
  }
  return image;
}

}  // namespace penumbra
