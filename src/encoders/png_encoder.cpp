// PNG on libpng, in memory: 8-bit grey or RGB with the header OpenImageIO's PNG writer
// gives (sRGB, gamma and chromaticities for sRGB data, the pixel offset, each string
// attribute a tEXt chunk in the order set), so the same pixels give the same bytes.
#include "encoders/encoders.h"

#include <png.h>
#include <zlib.h>

#include <csetjmp>
#include <cstring>

namespace penumbra::encoders {
namespace {

struct Sink {
  std::vector<unsigned char>* bytes;
  char error[256];
};

void append(png_structp png, png_bytep data, size_t n) {
  auto* sink = static_cast<Sink*>(png_get_io_ptr(png));
  sink->bytes->insert(sink->bytes->end(), data, data + n);
}

void flush(png_structp) {}

void onError(png_structp png, png_const_charp message) {
  auto* sink = static_cast<Sink*>(png_get_error_ptr(png));
  std::strncpy(sink->error, message, sizeof sink->error - 1);
  png_longjmp(png, 1);
}

void onWarning(png_structp, png_const_charp) {}

// Only plain data between setjmp and a longjmp out of libpng: no destructor is skipped.
bool writePng(const EncodeSpec& e, const unsigned char* pixels, const std::vector<png_text>& text, Sink& sink) {
  png_structp png = png_create_write_struct(PNG_LIBPNG_VER_STRING, &sink, onError, onWarning);
  if (!png) return false;
  png_infop info = png_create_info_struct(png);
  if (!info || setjmp(png_jmpbuf(png))) {
    png_destroy_write_struct(&png, info ? &info : nullptr);
    return false;
  }
  png_set_write_fn(png, &sink, append, flush);
  // OpenImageIO's choices: level 6, the default strategy (libpng's own is "filtered").
  png_set_compression_level(png, 6);
  png_set_compression_strategy(png, Z_DEFAULT_STRATEGY);
  static constexpr int kColour[] = {PNG_COLOR_TYPE_GRAY, PNG_COLOR_TYPE_GRAY_ALPHA, PNG_COLOR_TYPE_RGB,
                                    PNG_COLOR_TYPE_RGB_ALPHA};
  png_set_IHDR(png, info, png_uint_32(e.width), png_uint_32(e.height), 8, kColour[e.nchannels - 1],
               PNG_INTERLACE_NONE, PNG_COMPRESSION_TYPE_DEFAULT, PNG_FILTER_TYPE_DEFAULT);
  for (const ImageAttribute& a : e.attributes) {
    if (!a.isNumber && a.name == "oiio:ColorSpace" && a.text == "sRGB")
      png_set_sRGB_gAMA_and_cHRM(png, info, PNG_sRGB_INTENT_ABSOLUTE);
  }
  png_set_oFFs(png, info, e.x, e.y, PNG_OFFSET_PIXEL);
  if (!text.empty()) png_set_text(png, info, text.data(), int(text.size()));
  png_write_info(png, info);
  const size_t row = size_t(e.width) * size_t(e.nchannels);
  for (int y = 0; y < e.height; ++y) png_write_row(png, pixels + size_t(y) * row);
  png_write_end(png, info);
  png_destroy_write_struct(&png, &info);
  return true;
}

}  // namespace

// With alpha, OpenImageIO's writer un-premultiplies first: that file stays with it.
bool pngHandles(const EncodeSpec& e) {
  return e.fileType == PixelType::UInt8 && e.given == PixelType::UInt8 && e.channelTypes.empty() &&
         e.nchannels >= 1 && e.nchannels <= 4 && e.alphaChannel < 0 && e.width > 0 && e.height > 0;
}

std::string encodePng(const EncodeSpec& e, const void* pixels, std::vector<unsigned char>& bytes) {
  // Numbers have no tEXt form in OpenImageIO's writer, so it drops them; so does this one.
  std::vector<png_text> text;
  for (const ImageAttribute& a : e.attributes) {
    if (a.isNumber) continue;
    png_text t{};
    t.compression = PNG_TEXT_COMPRESSION_NONE;
    t.key = const_cast<char*>(a.name.c_str());
    t.text = const_cast<char*>(a.text.c_str());
    t.text_length = a.text.size();
    text.push_back(t);
  }
  const size_t raw = size_t(e.width) * size_t(e.height) * size_t(e.nchannels);
  bytes.clear();
  bytes.reserve(raw + raw / 64 + 65536);
  Sink sink{&bytes, {}};
  if (!writePng(e, static_cast<const unsigned char*>(pixels), text, sink)) {
    return sink.error[0] ? std::string("libpng: ") + sink.error : "libpng: cannot start a PNG";
  }
  return "";
}

}  // namespace penumbra::encoders
