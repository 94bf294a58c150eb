// Loads the image modules with dlopen on first use (core/module_loader.h): the
// executable has no link-time dependency on an image library, so its start-up never
// pays for loading one.
#include "core/image_codec.h"

#include "core/module_loader.h"

namespace penumbra {
namespace {

#ifndef PENUMBRA_IMAGE_MODULE
#define PENUMBRA_IMAGE_MODULE nullptr
#endif
#ifndef PENUMBRA_ENCODER_MODULE
#define PENUMBRA_ENCODER_MODULE nullptr
#endif

}  // namespace

const ImageCodec& imageCodec() {
  static const auto* const codec = static_cast<const ImageCodec*>(
      moduleEntry(kImageModuleName, kImageCodecEntry, PENUMBRA_IMAGE_MODULE, "image"));
  return *codec;
}

const ImageEncoder& imageEncoder() {
  static const auto* const encoder = static_cast<const ImageEncoder*>(
      moduleEntry(kImageEncoderModuleName, kImageEncoderEntry, PENUMBRA_ENCODER_MODULE, "image"));
  return *encoder;
}

}  // namespace penumbra
