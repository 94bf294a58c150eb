// EXR on OpenEXR, in memory: scanlines, zip, half or float channels, a part's data
// window inside its frame, string and float attributes, and the capture date, laid
// out as OpenImageIO's EXR writer lays them out.
#include "encoders/encoders.h"

#include <OpenEXR/ImfChannelList.h>
#include <OpenEXR/ImfFloatAttribute.h>
#include <OpenEXR/ImfFrameBuffer.h>
#include <OpenEXR/ImfHeader.h>
#include <OpenEXR/ImfIO.h>
#include <OpenEXR/ImfOutputFile.h>
#include <OpenEXR/ImfStringAttribute.h>

#include <algorithm>
#include <cstring>
#include <ctime>
#include <exception>

namespace penumbra::encoders {
namespace {

// OpenEXR writes forward, then seeks back once to fill in the offset table.
class MemoryStream final : public Imf::OStream {
 public:
  explicit MemoryStream(std::vector<unsigned char>& bytes) : Imf::OStream("memory"), bytes_(bytes) {}
  void write(const char c[], int n) override {
    if (pos_ + size_t(n) > bytes_.size()) bytes_.resize(pos_ + size_t(n));
    std::memcpy(bytes_.data() + pos_, c, size_t(n));
    pos_ += size_t(n);
  }
  uint64_t tellp() override { return pos_; }
  void seekp(uint64_t pos) override { pos_ = size_t(pos); }

 private:
  std::vector<unsigned char>& bytes_;
  size_t pos_ = 0;
};

Imf::PixelType exrType(PixelType t) { return t == PixelType::Float ? Imf::FLOAT : Imf::HALF; }

// The library's default channel names: R, G, B, A, then numbered.
std::string channelName(const EncodeSpec& e, int c) {
  if (!e.channelNames.empty()) return e.channelNames[size_t(c)];
  static const char* const kNames[] = {"R", "G", "B", "A"};
  return c < 4 && e.nchannels <= 4 ? kNames[c] : "channel" + std::to_string(c);
}

// The moment of writing, local time, in the form OpenImageIO gives "DateTime".
std::string captureDate() {
  const std::time_t now = std::time(nullptr);
  std::tm local{};
  localtime_r(&now, &local);
  char text[32];
  std::strftime(text, sizeof text, "%Y:%m:%d %H:%M:%S", &local);
  return text;
}

}  // namespace

bool exrHandles(const EncodeSpec& e) {
  return (e.given == PixelType::Float || e.given == PixelType::Half) && e.fileType != PixelType::UInt8 &&
         e.nchannels >= 1 && e.width > 0 && e.height > 0 &&
         (e.channelNames.empty() || int(e.channelNames.size()) == e.nchannels) &&
         (e.channelTypes.empty() || int(e.channelTypes.size()) == e.nchannels) &&
         std::none_of(e.channelTypes.begin(), e.channelTypes.end(), [](PixelType t) { return t == PixelType::UInt8; });
}

std::string encodeExr(const EncodeSpec& e, const void* pixels, std::vector<unsigned char>& bytes) {
  try {
    const int fullW = e.fullWidth > 0 ? e.fullWidth : e.width, fullH = e.fullWidth > 0 ? e.fullHeight : e.height;
    const int x0 = e.fullWidth > 0 ? e.x : 0, y0 = e.fullWidth > 0 ? e.y : 0;
    const Imath::Box2i display({0, 0}, {fullW - 1, fullH - 1});
    const Imath::Box2i data({x0, y0}, {x0 + e.width - 1, y0 + e.height - 1});
    Imf::Header header(display, data, 1.0f, Imath::V2f(0, 0), 1.0f, Imf::INCREASING_Y, Imf::ZIP_COMPRESSION);
    // The library's own keys ("oiio:...") stay out of the file, as its writer leaves
    // them; "DateTime" is EXR's capDate.
    for (const ImageAttribute& a : e.attributes) {
      if (a.name.rfind("oiio:", 0) == 0) continue;
      const std::string name = a.name == "DateTime" ? "capDate" : a.name;
      if (a.isNumber) header.insert(name, Imf::FloatAttribute(a.number));
      else header.insert(name, Imf::StringAttribute(a.text));
    }
    if (!header.findTypedAttribute<Imf::StringAttribute>("capDate"))
      header.insert("capDate", Imf::StringAttribute(captureDate()));

    // OpenEXR stores a slice only as its channel's own type: the pixels are converted
    // first (half rounds to nearest, as the image library's conversion does).
    std::vector<size_t> offset(size_t(e.nchannels) + 1, 0);
    for (int c = 0; c < e.nchannels; ++c) {
      const Imf::PixelType type = exrType(e.channelTypes.empty() ? e.fileType : e.channelTypes[size_t(c)]);
      offset[size_t(c) + 1] = offset[size_t(c)] + (type == Imf::FLOAT ? sizeof(float) : sizeof(Imath::half));
      header.channels().insert(channelName(e, c), Imf::Channel(type));
    }
    const size_t xStride = offset.back(), yStride = xStride * size_t(e.width), count = size_t(e.width) * size_t(e.height);
    std::vector<char> stored(yStride * size_t(e.height));
    for (size_t i = 0; i < count; ++i) {
      for (int c = 0; c < e.nchannels; ++c) {
        const size_t at = i * size_t(e.nchannels) + size_t(c);
        const float v = e.given == PixelType::Float ? static_cast<const float*>(pixels)[at]
                                                     : float(static_cast<const Imath::half*>(pixels)[at]);
        char* out = &stored[i * xStride + offset[size_t(c)]];
        if (offset[size_t(c) + 1] - offset[size_t(c)] == sizeof(float)) std::memcpy(out, &v, sizeof v);
        else {
          const Imath::half h(v);
          std::memcpy(out, &h, sizeof h);
        }
      }
    }
    // The frame buffer is addressed in the data window's coordinates.
    char* origin = stored.data() - ptrdiff_t(x0) * ptrdiff_t(xStride) - ptrdiff_t(y0) * ptrdiff_t(yStride);
    Imf::FrameBuffer frame;
    for (int c = 0; c < e.nchannels; ++c) {
      const Imf::PixelType type = offset[size_t(c) + 1] - offset[size_t(c)] == sizeof(float) ? Imf::FLOAT : Imf::HALF;
      frame.insert(channelName(e, c), Imf::Slice(type, origin + offset[size_t(c)], xStride, yStride));
    }
    // Room for the file uncompressed, so the buffer never grows by copying.
    bytes.clear();
    bytes.reserve(stored.size() + 65536);
    MemoryStream stream(bytes);
    Imf::OutputFile file(stream, header);
    file.setFrameBuffer(frame);
    file.writePixels(e.height);
  } catch (const std::exception& ex) {
    return std::string("OpenEXR: ") + ex.what();
  }
  return "";
}

}  // namespace penumbra::encoders
