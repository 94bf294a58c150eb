// The image module's codec on OpenImageIO: files opened for reading, images encoded in
// memory, header attributes; and the one symbol the module exports.
#include "images/oiio_parts.h"

#include "core/emission_map.h"

#include <OpenImageIO/filesystem.h>
#include <OpenImageIO/imageio.h>

#include <algorithm>

namespace penumbra::oiio {

namespace {

OIIO::TypeDesc typeOf(PixelType t) {
  switch (t) {
    case PixelType::UInt8: return OIIO::TypeDesc::UINT8;
    case PixelType::Half: return OIIO::TypeDesc::HALF;
    case PixelType::Float: return OIIO::TypeDesc::FLOAT;
  }
  return OIIO::TypeDesc::UNKNOWN;
}

OIIO::stride_t strideOf(std::ptrdiff_t s) { return s == kAutoStride ? OIIO::AutoStride : OIIO::stride_t(s); }

class Reader final : public ImageReader {
 public:
  explicit Reader(std::unique_ptr<OIIO::ImageInput> in) : in_(std::move(in)) {
    const OIIO::ImageSpec& s = in_->spec();
    info_.x = s.x;
    info_.y = s.y;
    info_.z = s.z;
    info_.width = s.width;
    info_.height = s.height;
    info_.depth = s.depth;
    info_.nchannels = s.nchannels;
    info_.tileWidth = s.tile_width;
    info_.tileHeight = s.tile_height;
    info_.alphaChannel = s.alpha_channel;
    info_.fullWidth = s.full_width;
    info_.fullHeight = s.full_height;
    info_.channelNames = s.channelnames;
    for (const OIIO::ParamValue& p : s.extra_attribs) {
      if (p.type() == OIIO::TypeDesc::STRING) info_.attributes.emplace_back(p.name().string(), p.get_string());
    }
    info_.formatName = in_->format_name();
    info_.pixelType = s.format.c_str();
    info_.pixelBytes = s.format.size();
  }
  const ImageInfo& info() const override { return info_; }
  bool readFloat(int xbegin, int xend, int ybegin, int yend, int chbegin, int chend, float* data,
                 std::ptrdiff_t xstride, std::ptrdiff_t ystride) override {
    const OIIO::ImageSpec& spec = in_->spec();
    const bool read = spec.tile_width > 0
                          ? in_->read_tiles(0, 0, xbegin, xend, ybegin, yend, spec.z, spec.z + 1, chbegin, chend,
                                            OIIO::TypeDesc::FLOAT, data, strideOf(xstride), strideOf(ystride))
                          : in_->read_scanlines(0, 0, ybegin, yend, spec.z, chbegin, chend, OIIO::TypeDesc::FLOAT,
                                                data, strideOf(xstride), strideOf(ystride));
    return read && !in_->has_error();
  }
  bool readChannelBytes(int channel, uint8_t* data) override {
    return in_->read_image(0, 0, channel, channel + 1, OIIO::TypeDesc::UINT8, data);
  }
  std::string error() override { return in_->geterror(); }

 private:
  std::unique_ptr<OIIO::ImageInput> in_;
  ImageInfo info_;
};

class Codec final : public ImageCodec {
 public:
  std::unique_ptr<ImageReader> open(const std::string& path, std::string& error) const override {
    auto in = OIIO::ImageInput::open(path);
    if (!in) {
      error = OIIO::geterror();
      return nullptr;
    }
    return std::make_unique<Reader>(std::move(in));
  }

  // OIIO's PNG writer does not report a short write, so it never touches the disk:
  // the caller writes the bytes through its checked write-and-rename.
  std::string encode(const std::string& path, const EncodeSpec& e, const void* pixels,
                     std::vector<unsigned char>& bytes) const override {
    OIIO::ImageSpec spec(e.width, e.height, e.nchannels, typeOf(e.fileType));
    if (!e.channelNames.empty()) spec.channelnames = e.channelNames;
    for (PixelType t : e.channelTypes) spec.channelformats.push_back(typeOf(t));
    if (e.alphaChannel >= 0) spec.alpha_channel = e.alphaChannel;
    if (e.fullWidth > 0) {
      spec.x = e.x;
      spec.y = e.y;
      spec.full_x = spec.full_y = 0;
      spec.full_width = e.fullWidth;
      spec.full_height = e.fullHeight;
    }
    for (const ImageAttribute& a : e.attributes) {
      if (a.isNumber) spec.attribute(a.name, a.number);
      else spec.attribute(a.name, a.text);
    }
    auto out = OIIO::ImageOutput::create(path);
    if (!out) return failed(OIIO::geterror());
    if (!out->supports("ioproxy")) return std::string(out->format_name()) + " cannot be encoded in memory";
    // Room for the file uncompressed (zip's worst case adds < 1/64), so the buffer never
    // grows by copying; pages it leaves untouched cost no memory.
    const size_t raw = spec.image_bytes(/*native=*/true);
    bytes.reserve(raw + raw / 64 + 65536);
    OIIO::Filesystem::IOVecOutput proxy(bytes);
    if (!out->set_ioproxy(&proxy) || !out->open(path, spec)) return failed(out->geterror());
    if (!out->write_image(typeOf(e.given), pixels)) {
      const std::string reason = out->geterror();
      out->close();
      return failed(reason);
    }
    if (!out->close()) return failed(out->geterror());
    out.reset();  // the writer may still hold the proxy until it is destroyed
    return "";
  }

  std::string attribute(const std::string& path, const std::string& name) const override {
    auto in = OIIO::ImageInput::open(path);
    if (!in) {
      (void)OIIO::geterror();  // clear OIIO's pending error: a missing file is a plain answer here
      return "";
    }
    const std::string value = in->spec().get_string_attribute(name);
    in->close();
    return value;
  }

  std::string readLinear(const std::string& path, Image& image) const override {
    return oiio::readLinear(path, image);
  }
  EmissionMap readEmissionMap(const std::string& path, const UvTransform& transform, int maxSide) const override {
    return oiio::readEmissionMap(path, transform, maxSide);
  }
  ImageComparison compare(const Image& image, const Image& reference) const override {
    return oiio::compare(image, reference);
  }
  std::string drawContactSheet(const std::vector<std::string>& images,
                               const std::vector<std::vector<std::string>>& labels, Image& sheet) const override {
    return oiio::drawContactSheet(images, labels, sheet);
  }
  std::unique_ptr<TextureSampler> textures(const std::vector<std::string>& paths,
                                           const std::vector<bool>& data) const override {
    return oiio::textures(paths, data);
  }
};

}  // namespace
}  // namespace penumbra::oiio

extern "C" __attribute__((visibility("default"))) const penumbra::ImageCodec* penumbra_image_codec() {
  static const penumbra::oiio::Codec codec;
  return &codec;
}
