// glTF metallic-roughness materials mapped onto penumbra's Material, and their
// base-colour images as texture files (embedded ones written to the texture cache).
#pragma once
#include "io/model_import.h"
#include <tiny_gltf.h>
#include <string>
#include <vector>

namespace penumbra {

// One ModelMaterial per model.materials entry, in order (docs/scene-format.md, "glTF").
// `path` is the glTF file, for messages; `folder` its folder (absolute), the only
// place image URIs may name. Throws ModelError.
std::vector<ModelMaterial> gltfMaterials(const tinygltf::Model& model, const std::string& path,
                                         const std::string& folder);

// tinygltf's image callback: keeps the encoded bytes (OpenImageIO decodes them later).
bool keepEncodedImage(tinygltf::Image* image, const int index, std::string* err, std::string* warn,
                      int width, int height, const unsigned char* bytes, int size, void* user);

}  // namespace penumbra
