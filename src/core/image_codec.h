// The seam to the image library: every decode, encode, filtered texture lookup and
// image arithmetic goes through ImageCodec, which a shared module (OpenImageIO and its
// codecs) provides; the module is loaded on first use, so a run that never touches an
// image never loads the library's hundreds of dependencies.
#pragma once
#include "core/image.h"
#include "core/texture_sampling.h"
#include <cstddef>
#include <cstdint>
#include <memory>
#include <string>
#include <utility>
#include <vector>

namespace penumbra {

struct EmissionMap;
struct UvTransform;

// What a decoder found in an image file's header.
struct ImageInfo {
  int x = 0, y = 0, z = 0;  // the data window's origin
  int width = 0, height = 0, depth = 1, nchannels = 0;
  int tileWidth = 0, tileHeight = 0;  // 0: scanlines
  int alphaChannel = -1;              // the channel the file names alpha, -1 if none
  int fullWidth = 0, fullHeight = 0;  // the display window: the whole frame a part belongs to
  std::vector<std::string> channelNames;
  std::vector<std::pair<std::string, std::string>> attributes;  // the header's string attributes
  std::string formatName;             // the decoder: "openexr", "hdr", "png", ...
  std::string pixelType;              // the stored values: "half", "uint8", ...
  size_t pixelBytes = 0;              // bytes of one stored value
};

// Stride value meaning "packed", as the image library spells it.
inline constexpr std::ptrdiff_t kAutoStride = PTRDIFF_MIN;

// An image file opened for reading, its header decoded.
class ImageReader {
 public:
  virtual ~ImageReader() = default;
  virtual const ImageInfo& info() const = 0;
  // Pixels [xbegin, xend) x [ybegin, yend), channels [chbegin, chend), as float at
  // `data` with strides in bytes: whole tiles of a tiled file, whole rows (the x range
  // ignored) of a scanline file. False when decoding fails (then error() says why).
  virtual bool readFloat(int xbegin, int xend, int ybegin, int yend, int chbegin, int chend, float* data,
                         std::ptrdiff_t xstride, std::ptrdiff_t ystride) = 0;
  // The whole image's channel `channel` as bytes, the library rounding and clamping.
  virtual bool readChannelBytes(int channel, uint8_t* data) = 0;
  virtual std::string error() = 0;
};

// What to encode: the header of the file written, and the pixels' layout.
enum class PixelType { UInt8, Half, Float };
struct ImageAttribute {
  std::string name;
  std::string text;        // a string attribute, unless isNumber
  float number = 0.0f;
  bool isNumber = false;
};
struct EncodeSpec {
  int width = 0, height = 0, nchannels = 0;
  // A part of a frame (EXR): its data window's origin and the frame's size; 0: none.
  int x = 0, y = 0, fullWidth = 0, fullHeight = 0;
  PixelType fileType = PixelType::UInt8;       // the file's values
  std::vector<std::string> channelNames;       // empty: the library's default names
  std::vector<PixelType> channelTypes;         // empty: all fileType
  int alphaChannel = -1;
  std::vector<ImageAttribute> attributes;      // in the order they are set
  PixelType given = PixelType::UInt8;          // the interleaved pixels handed over
};

// Error figures of an image against a reference from the library's image maths.
struct ImageComparison {
  double rmse = 0.0, maxError = 0.0;
  double psnr = 0.0;           // of both clamped to [0, 1]
  double relMse = 0.0;         // mean of (a - r)^2 / (r^2 + 0.01)
  double referenceMean = 0.0;  // over pixels and channels
};

// Filtered, MIP-mapped lookups into a set of textures (grey replicated, sRGB-encoded
// colour files linearised after filtering). Thread-safe; no allocation per lookup.
class TextureSampler {
 public:
  virtual ~TextureSampler() = default;
  // Texture `index` at (s, t), filter widths ds along s and dt along t, wrapped and
  // filtered as `how` says.
  virtual Color sample(int index, float s, float t, float ds, float dt, const TextureSampling& how) const = 0;
};

class ImageCodec {
 public:
  virtual ~ImageCodec() = default;
  // Null with the library's error in `error` when `path` does not open.
  virtual std::unique_ptr<ImageReader> open(const std::string& path, std::string& error) const = 0;
  // The file `path` names (its extension picks the format) encoded into `bytes`;
  // "" or why not.
  virtual std::string encode(const std::string& path, const EncodeSpec& spec, const void* pixels,
                             std::vector<unsigned char>& bytes) const = 0;
  // A string attribute of the file's header, "" when the file or attribute is missing.
  virtual std::string attribute(const std::string& path, const std::string& name) const = 0;
  // Any readable image as linear RGB into `image` (io/image_io.h readImage); "" or
  // why not.
  virtual std::string readLinear(const std::string& path, Image& image) const = 0;
  // An emissive texture as linear RGB box-filtered to at most `maxSide` texels a side
  // (io/emission_map_reader.h); throws InputError.
  virtual EmissionMap readEmissionMap(const std::string& path, const UvTransform& transform,
                                      int maxSide) const = 0;
  // Throws InputError when the sizes differ.
  virtual ImageComparison compare(const Image& image, const Image& reference) const = 0;
  // The contact sheet of `images` (linear files), labelled with up to two `labels`
  // lines each, into `sheet`; "" or why not (io/contact_sheet.h).
  virtual std::string drawContactSheet(const std::vector<std::string>& images,
                                       const std::vector<std::vector<std::string>>& labels, Image& sheet) const = 0;
  // Throws InputError naming a file that cannot be read; `data[i]` says texture i
  // holds values (never sRGB-decoded).
  virtual std::unique_ptr<TextureSampler> textures(const std::vector<std::string>& paths,
                                                   const std::vector<bool>& data) const = 0;
};

// PNG and EXR encoding in a module of its own on libpng and OpenEXR, the two formats a
// render writes: writing an output never loads OpenImageIO's hundreds of libraries.
class ImageEncoder {
 public:
  virtual ~ImageEncoder() = default;
  // Whether encode() takes this file and spec; else the image module encodes it.
  virtual bool handles(const std::string& path, const EncodeSpec& spec) const = 0;
  // As ImageCodec::encode, with the same bytes where the image library's encoder is
  // deterministic (an EXR's capDate is the time of writing).
  virtual std::string encode(const std::string& path, const EncodeSpec& spec, const void* pixels,
                             std::vector<unsigned char>& bytes) const = 0;
};

// The module's one exported symbol: returns its codec.
inline constexpr const char* kImageCodecEntry = "penumbra_image_codec";
// The module's file name; found in the process (a test links it), beside the running
// executable, or where the build put it.
inline constexpr const char* kImageModuleName = "libpenumbra_images.so";

// The codec, loading the module on first call (thread-safe). Throws std::runtime_error
// naming the module when it cannot be loaded.
const ImageCodec& imageCodec();

inline constexpr const char* kImageEncoderEntry = "penumbra_image_encoder";
inline constexpr const char* kImageEncoderModuleName = "libpenumbra_encoders.so";
// The encoder, loading its module on first call (thread-safe), as imageCodec().
const ImageEncoder& imageEncoder();

}  // namespace penumbra
