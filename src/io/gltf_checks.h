// The checks a parsed glTF model meets before any of it is used: accessor bytes
// inside their views and buffers (checked 64-bit arithmetic), the node graph a
// forest of invertible transforms, and lights, materials, cameras and primitives
// within what the spec and penumbra allow. Every refusal names the JSON path.
#pragma once
#include "io/load_limits.h"
#include <glm/mat4x4.hpp>
#include <tiny_gltf.h>
#include <cstdint>
#include <string>
#include <vector>

namespace penumbra {

// Throws ModelError "glTF file <path>: <where>: <problem>".
[[noreturn]] void gltfFail(const std::string& path, const std::string& where, const std::string& problem);

// Where accessor elements lie: `count` elements of `components` x `componentSize`
// bytes, `stride` apart from `data`; data == nullptr: no buffer view (all zeros).
struct AccessorSpan {
  const unsigned char* data = nullptr;
  uint64_t count = 0, stride = 0;
  int components = 0, componentSize = 0, componentType = 0;
  bool normalized = false;
};

// Accessor `index` (named by `ref`, the JSON path that refers to it) with every
// byte it names proven inside its view and buffer.
AccessorSpan accessorSpan(const tinygltf::Model& m, int index, const std::string& ref, const std::string& path);

// A node's local transform: its matrix, or T * R * S with R's quaternion normalised.
glm::dmat4 nodeMatrix(const tinygltf::Node& n);

// Structure and values: the node forest (returns the root nodes to load), node
// transforms, primitives, lights, materials' extensions and cameras. Things skipped
// (points and lines, cameras neither perspective nor orthographic) are appended to `warnings`.
std::vector<int> checkGltfModel(const tinygltf::Model& m, const std::string& path, std::vector<std::string>& warnings);

// A material's values (gltf_material_checks.cpp): its extensions' numbers, alphaMode,
// and every texture's KHR_texture_transform bounded as TEXCOORD_0 is.
void checkGltfMaterial(const tinygltf::Material& g, const std::string& where, const std::string& path);

// Refuses the model when the meshes it makes (every primitive under every node that
// instances it) with the buffers already held would need more than limits.maxBytes.
void checkGltfBudget(const tinygltf::Model& m, const std::vector<int>& roots, const std::string& path,
                     const LoadLimits& limits);

}  // namespace penumbra
