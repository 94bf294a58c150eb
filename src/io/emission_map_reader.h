// Emissive textures at load: the image decoded once into the linear texels a textured
// mesh light samples (core/emission_map.h), reduced to a bounded size for lighting.
#pragma once
#include "core/emission_map.h"
#include <string>

namespace penumbra {

// Lighting reads at most this many texels a side: the light's tables weigh triangles,
// and the glow a camera ray sees comes from the full texture (trace/texture_lookup).
inline constexpr int kEmissionMapSize = 512;

// `path`'s colour (grey replicated, alpha dropped), sRGB-decoded as textures are, box-
// filtered down to kEmissionMapSize a side; placed by `transform`. Throws InputError
// naming the file when it cannot be decoded.
EmissionMap readEmissionMap(const std::string& path, const UvTransform& transform);

}  // namespace penumbra
