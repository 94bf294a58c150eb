// glTF 2.0 files (.gltf, .glb) through tinygltf: meshes under their node
// transforms, metallic-roughness materials, its cameras, punctual lights.
#pragma once
#include "io/model_import.h"
#include <string>

namespace penumbra {

// Loads the default scene (else scene 0, else every root node) of `path`: every
// triangle primitive as a mesh in world space (node matrices or TRS composed down
// the tree; normals by the inverse transpose; mirroring nodes flip the winding),
// TEXCOORD_0 as uvs (glTF's top-left origin is OIIO's), no normals = flat shading.
// Materials map as docs/scene-format.md ("glTF") says; KHR_lights_punctual point
// and spot lights become point lights (the cone is dropped), directional lights
// directional; candela and lux are read as W/sr and W/m^2. Throws ModelError naming
// the file and JSON path for anything docs/scene-format.md lists as refused, before
// reading files outside the model's folder or allocating beyond `limits`.
LoadedModel loadGltfModel(const std::string& path, const LoadLimits& limits = {});

}  // namespace penumbra
