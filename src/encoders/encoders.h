// The encoder module's two formats behind core/image_codec.h's ImageEncoder: PNG on
// libpng, EXR on OpenEXR, each laid out as OpenImageIO's writers lay them out.
#pragma once
#include "core/image_codec.h"

namespace penumbra::encoders {

bool pngHandles(const EncodeSpec& spec);
std::string encodePng(const EncodeSpec& spec, const void* pixels, std::vector<unsigned char>& bytes);

bool exrHandles(const EncodeSpec& spec);
std::string encodeExr(const EncodeSpec& spec, const void* pixels, std::vector<unsigned char>& bytes);

}  // namespace penumbra::encoders
