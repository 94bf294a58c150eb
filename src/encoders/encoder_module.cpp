// The encoder module: PNG and EXR chosen by the target's extension, and the one symbol
// the module exports.
#include "encoders/encoders.h"

#include <algorithm>
#include <cctype>

namespace penumbra::encoders {
namespace {

std::string lowerExtension(const std::string& path) {
  const size_t slash = path.rfind('/'), dot = path.rfind('.');
  if (dot == std::string::npos || (slash != std::string::npos && dot < slash)) return "";
  std::string ext = path.substr(dot);
  std::transform(ext.begin(), ext.end(), ext.begin(), [](unsigned char c) { return char(std::tolower(c)); });
  return ext;
}

class Encoder final : public ImageEncoder {
 public:
  bool handles(const std::string& path, const EncodeSpec& spec) const override {
    const std::string ext = lowerExtension(path);
    return (ext == ".png" && pngHandles(spec)) || (ext == ".exr" && exrHandles(spec));
  }
  std::string encode(const std::string& path, const EncodeSpec& spec, const void* pixels,
                     std::vector<unsigned char>& bytes) const override {
    const std::string ext = lowerExtension(path);
    if (ext == ".png" && pngHandles(spec)) return encodePng(spec, pixels, bytes);
    if (ext == ".exr" && exrHandles(spec)) return encodeExr(spec, pixels, bytes);
    return "the encoder module does not write this kind of image";
  }
};

}  // namespace
}  // namespace penumbra::encoders

extern "C" __attribute__((visibility("default"))) const penumbra::ImageEncoder* penumbra_image_encoder() {
  static const penumbra::encoders::Encoder encoder;
  return &encoder;
}
