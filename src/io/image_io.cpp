// Image file I/O through the image module (core/image_codec.h): the sRGB transfer
// curve, the choice of writer by extension, encoding in memory for the checked
// write-and-rename that keeps targets whole, and the cheap test that a file is whole.
#include "io/image_io.h"
#include "core/color.h"

#include "core/error.h"
#include "core/image_codec.h"
#include "io/aov_display.h"
#include "io/image_encode.h"
#include "io/image_file_header.h"
#include "io/image_header.h"
#include "io/temp_file.h"

#include <fcntl.h>
#include <sys/stat.h>
#include <unistd.h>

#include <algorithm>
#include <cctype>
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

// PNG alpha is straight and linear (the PNG specification): light over a transparent
// background (which carries coverage) is unpremultiplied before its display transform;
// a pixel no sample hit is (0, 0, 0, 0). Depth and normal PNGs stay pictures, RGB.
bool pngAlpha(const Image& image) { return !geometric(image) && !image.coverage.empty(); }
uint8_t toAlpha8(float coverage) {
  return static_cast<uint8_t>(std::floor(std::clamp(coverage, 0.0f, 1.0f) * 255.0f + 0.5f));
}

// One EXR layer: its channel-name prefix ("" for a plain RGB file) and its image.
struct ExrLayer {
  std::string name;
  const Image* image;
};

// The EXR header and interleaved pixels of `layers`: R, G, B per layer (half for
// radiance, float for geometric views) and, for a geometric view, A = its coverage.
EncodeSpec exrSpec(const std::vector<ExrLayer>& layers, std::vector<float>& floats) {
  std::vector<std::string> names;
  std::vector<PixelType> formats;
  bool anyFloat = false;
  for (const ExrLayer& l : layers) {
    const std::string prefix = l.name.empty() ? "" : l.name + ".";
    const bool exact = geometric(*l.image);
    anyFloat = anyFloat || exact;
    for (const char* c : {"R", "G", "B", "A"}) {
      if (*c == 'A' && l.image->coverage.empty()) continue;
      names.push_back(prefix + c);
      formats.push_back(exact ? PixelType::Float : PixelType::Half);
    }
  }
  const Image& first = *layers.front().image;
  const size_t n = names.size();
  EncodeSpec spec;
  spec.width = first.width;
  spec.height = first.height;
  spec.nchannels = static_cast<int>(n);
  spec.fileType = anyFloat ? PixelType::Float : PixelType::Half;
  spec.given = PixelType::Float;  // the library converts to the file's half
  // Only what differs from the default, so a radiance EXR keeps its old header.
  if (!layers.front().name.empty()) spec.channelNames = names;
  if (anyFloat && std::any_of(formats.begin(), formats.end(), [](auto f) { return f != PixelType::Float; }))
    spec.channelTypes = formats;
  if (layers.size() == 1 && n == 4) spec.alphaChannel = 3;
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

// Library error strings can span lines; InputError messages are one line.
std::string oneLine(std::string text) {
  std::replace(text.begin(), text.end(), '\n', ' ');
  const char* space = " \t\n\r\f\v";
  const size_t first = text.find_first_not_of(space);
  if (first == std::string::npos) return "unknown error";
  return text.substr(first, text.find_last_not_of(space) + 1 - first);
}

std::string lowerExtension(const std::string& path) {
  std::string ext = fs::path(path).extension().string();
  std::transform(ext.begin(), ext.end(), ext.begin(), [](unsigned char c) { return char(std::tolower(c)); });
  return ext;
}

void setAttribute(EncodeSpec& spec, const std::string& name, const std::string& text) {
  spec.attributes.push_back({name, text, 0.0f, false});
}

[[noreturn]] void writeFailed(const std::string& path, const std::string& reason) {
  throw InputError(path + ": cannot write image: " + oneLine(reason));
}

}  // namespace

// Encodes the image in memory (the writer chosen by the target's extension; the
// encoder module where it takes the file, else the image module), then writes the
// bytes through the one checked write-and-rename (temp_file.h).
void writeAtomically(const std::string& path, const EncodeSpec& spec, const void* pixels) {
  std::vector<unsigned char> bytes;
  const ImageEncoder& encoder = imageEncoder();
  const std::string problem = encoder.handles(path, spec) ? encoder.encode(path, spec, pixels, bytes)
                                                          : imageCodec().encode(path, spec, pixels, bytes);
  if (!problem.empty()) writeFailed(path, problem);
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
  const std::string ext = lowerExtension(path);
  if (ext != ".png" && ext != ".exr") {
    throw InputError(path + ": unsupported image extension '" + fs::path(path).extension().string() +
                     "' (use .png or .exr)");
  }
  const std::string problem = outputPathProblem(path);
  if (!problem.empty()) writeFailed(path, problem);
}

void writeImage(const std::string& path, const Image& image, const ImageMetadata& metadata,
                const DisplayOptions& display) {
  checkImageOutputPath(path);
  Encoding encoding = lowerExtension(path) == ".png" ? Encoding::Srgb8 : Encoding::Exr;
  if (image.width <= 0 || image.height <= 0 ||
      image.pixels.size() != static_cast<size_t>(image.width) * image.height ||
      (!image.coverage.empty() && image.coverage.size() != image.pixels.size())) {
    writeFailed(path, "image is empty or its pixel count does not match its size");
  }
  refuseNan(path, image);

  std::vector<uint8_t> bytes;
  std::vector<float> floats;
  EncodeSpec spec;
  const void* pixels = nullptr;
  if (encoding == Encoding::Srgb8) {
    const Image shown = aovDisplay(image);  // depth and normals as pictures; radiance as is
    const int channels = pngAlpha(image) ? 4 : 3;
    const size_t count = shown.pixels.size() * channels;
    spec.width = image.width;
    spec.height = image.height;
    spec.nchannels = channels;
    if (channels == 4) {
      spec.alphaChannel = 3;
      setAttribute(spec, "oiio:UnassociatedAlpha", "1");  // as given, not divided again
    }
    spec.fileType = spec.given = PixelType::UInt8;
    setAttribute(spec, "oiio:ColorSpace", "sRGB");
    // Only when asked for: a default PNG keeps today's bytes, metadata included.
    if (display.tone != ToneMap::Clamp || display.exposure != 0.0f) {
      setAttribute(spec, "penumbra:tonemap", toneMapName(display.tone));
      spec.attributes.push_back({"penumbra:exposure", "", display.exposure, true});
    }
    bytes.resize(count);
    for (size_t i = 0; i < shown.pixels.size(); ++i) {
      const float a = channels == 4 ? image.coverage[i] : 1.0f;
      uint8_t* out = &bytes[i * channels];
      const Color c = a > 0.0f ? displayColor(shown.pixels[i] / a, display) : Color(0.0f);
      for (int k = 0; k < 3; ++k) out[k] = a > 0.0f ? toSrgb8(c[k]) : 0;
      if (channels == 4) out[3] = toAlpha8(a);
    }
    pixels = bytes.data();
  } else {
    spec = exrSpec({{"", &image}}, floats);
    setAttribute(spec, "oiio:ColorSpace", "Linear");
    pixels = floats.data();
  }
  setAttribute(spec, "Software", "penumbra");
  for (const auto& [key, value] : metadata) setAttribute(spec, key, value);

  writeAtomically(path, spec, pixels);
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
  EncodeSpec spec = exrSpec(parts, floats);
  setAttribute(spec, "oiio:ColorSpace", "Linear");
  setAttribute(spec, "Software", "penumbra");
  for (const auto& [key, value] : metadata) setAttribute(spec, key, value);
  writeAtomically(path, spec, floats.data());
}

bool imageComplete(const std::string& path) {
  std::string tail = path.substr(path.size() - std::min<size_t>(path.size(), 4));
  std::transform(tail.begin(), tail.end(), tail.begin(), [](unsigned char c) { return char(std::tolower(c)); });
  if (tail == ".png") return pngEndsWhole(path);
  std::error_code ec;
  if (!fs::exists(path, ec)) return false;
  if (const std::optional<bool> whole = exrLastChunkWhole(path)) return *whole;
  // Another format, or a tiled EXR: the header opens and the last row decodes.
  std::string problem;
  const std::unique_ptr<ImageReader> in = openImage(path, path, problem);
  if (!in) return false;
  const ImageInfo& info = in->info();
  if (info.width <= 0 || info.height <= 0 || info.nchannels <= 0 || (info.tileWidth > 0 && info.tileHeight <= 0))
    return false;
  return lastRowProblem(*in, path).empty();
}

std::string readImageAttribute(const std::string& path, const std::string& name) {
  std::error_code ec;
  if (!fs::exists(path, ec)) return "";
  if (std::optional<std::string> value = penumbraAttribute(path, name)) return *value;
  return imageCodec().attribute(path, name);
}

Image readImage(const std::string& path) {
  Image image;
  const std::string problem = imageCodec().readLinear(path, image);
  if (!problem.empty()) throw InputError(path + ": cannot read image: " + oneLine(problem));
  return image;
}

}  // namespace penumbra
