// glTF samplers: a texture's wrapS/wrapT and mag/min filters as penumbra's
// TextureSampling (docs/scene-format.md, "glTF").
#pragma once
#include "core/texture_sampling.h"
#include <tiny_gltf.h>
#include <optional>
#include <string>

namespace penumbra {

// The sampler of texture `index` (none for index < 0); a texture without one
// repeats in both directions and leaves the filters to the texture system. `path`
// names the file in messages; throws ModelError for a sampler index or enum value
// the spec does not allow.
std::optional<TextureSampling> gltfTextureSampling(const tinygltf::Model& model, int index, const std::string& path);

}  // namespace penumbra
