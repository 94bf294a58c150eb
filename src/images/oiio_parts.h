// The image module's parts behind core/image_codec.h, each on OpenImageIO; the codec
// (oiio_codec.cpp) hands them out.
#pragma once
#include "core/image_codec.h"
#include <OpenImageIO/typedesc.h>

namespace penumbra::oiio {

// Whether stored values of `type` are integers (then sRGB unless they say otherwise).
inline bool integerType(OIIO::TypeDesc type) {
  return type.basetype != OIIO::TypeDesc::FLOAT && type.basetype != OIIO::TypeDesc::HALF &&
         type.basetype != OIIO::TypeDesc::DOUBLE;
}

// A failure's reason, never "" (which means success).
inline std::string failed(const std::string& reason) { return reason.empty() ? "unknown error" : reason; }

std::string readLinear(const std::string& path, Image& image);
EmissionMap readEmissionMap(const std::string& path, const UvTransform& transform, int maxSide);
ImageComparison compare(const Image& image, const Image& reference);
std::string drawContactSheet(const std::vector<std::string>& images,
                             const std::vector<std::vector<std::string>>& labels, Image& sheet);
std::unique_ptr<TextureSampler> textures(const std::vector<std::string>& paths, const std::vector<bool>& data);

}  // namespace penumbra::oiio
