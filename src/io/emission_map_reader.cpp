// Emissive textures decoded through the image module: channels to RGB, sRGB to
// linear before any averaging, resized to the lighting size; what may not emit cleared.
#include "io/emission_map_reader.h"

#include "core/image_codec.h"

#include <cmath>

namespace penumbra {

EmissionMap readEmissionMap(const std::string& path, const UvTransform& transform) {
  EmissionMap map = imageCodec().readEmissionMap(path, transform, kEmissionMapSize);
  for (Color& c : map.texels) {  // a float file may hold negatives or NaN: they emit nothing
    for (int k = 0; k < 3; ++k) c[k] = c[k] > 0.0f && std::isfinite(c[k]) ? c[k] : 0.0f;
  }
  return map;
}

}  // namespace penumbra
