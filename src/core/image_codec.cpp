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
  static const ImageCodec* const codec =
      moduleObject<ImageCodec>(kImageModuleName, kImageCodecEntry, PENUMBRA_IMAGE_MODULE, "image");
  return *codec;
}

const ImageEncoder& imageEncoder() {
  static const ImageEncoder* const encoder =
      moduleObject<ImageEncoder>(kImageEncoderModuleName, kImageEncoderEntry, PENUMBRA_ENCODER_MODULE, "image");
  return *encoder;
}

}  // namespace penumbra
