// Emissive textures decoded through OpenImageIO's ImageBuf: channels to RGB, sRGB to
// linear before any averaging, then ImageBufAlgo's resize to the lighting size.
#include "io/emission_map_reader.h"

#include "core/color.h"
#include "core/error.h"

#include <OpenImageIO/imagebuf.h>
#include <OpenImageIO/imagebufalgo.h>
#include <algorithm>
#include <cmath>

namespace penumbra {

EmissionMap readEmissionMap(const std::string& path, const UvTransform& transform) {
  auto fail = [&](const std::string& why) { throw InputError(path + ": cannot read emissive texture: " + why); };
  OIIO::ImageBuf source(path);
  if (!source.read(0, 0, true, OIIO::TypeDesc::FLOAT)) fail(source.geterror());
  const OIIO::ImageSpec& spec = source.spec();
  const OIIO::TypeDesc::BASETYPE stored = OIIO::TypeDesc::BASETYPE(source.nativespec().format.basetype);
  const bool integer = stored != OIIO::TypeDesc::FLOAT && stored != OIIO::TypeDesc::HALF &&
                       stored != OIIO::TypeDesc::DOUBLE;
  const bool srgb = isSrgbEncoded(source.nativespec().get_string_attribute("oiio:ColorSpace"), integer);
  // RGB, or the grey channel three times (texture lookups read grey the same way).
  const int order[3] = {0, spec.nchannels >= 3 ? 1 : 0, spec.nchannels >= 3 ? 2 : 0};
  OIIO::ImageBuf rgb = OIIO::ImageBufAlgo::channels(source, 3, order);
  if (rgb.has_error()) fail(rgb.geterror());
  if (srgb) {
    for (OIIO::ImageBuf::Iterator<float> it(rgb); !it.done(); ++it) {
      for (int c = 0; c < 3; ++c) it[c] = float(srgbDecode(it[c]));
    }
  }
  const int largest = std::max(spec.width, spec.height);
  if (largest > kEmissionMapSize) {
    const int w = std::max(1, spec.width * kEmissionMapSize / largest);
    const int h = std::max(1, spec.height * kEmissionMapSize / largest);
    rgb = OIIO::ImageBufAlgo::resize(rgb, "box", 0.0f, OIIO::ROI(0, w, 0, h, 0, 1, 0, 3));
    if (rgb.has_error()) fail(rgb.geterror());
  }
  EmissionMap map;
  map.width = rgb.spec().width;
  map.height = rgb.spec().height;
  map.transform = transform;
  map.texels.resize(size_t(map.width) * size_t(map.height));
  if (!rgb.get_pixels(OIIO::ROI(0, map.width, 0, map.height, 0, 1, 0, 3), OIIO::TypeDesc::FLOAT, map.texels.data())) {
    fail(rgb.geterror());
  }
  for (Color& c : map.texels) {  // a float file may hold negatives or NaN: they emit nothing
    for (int k = 0; k < 3; ++k) c[k] = c[k] > 0.0f && std::isfinite(c[k]) ? c[k] : 0.0f;
  }
  return map;
}

}  // namespace penumbra
