// A glTF primitive's vertex attributes read straight into a mesh's float arrays:
// every element of an accessor as doubles, one at a time (forEachElement), and the
// attributes beyond POSITION, NORMAL and TEXCOORD_0: TANGENT and COLOR_0.
#pragma once
#include "io/gltf_checks.h"
#include "io/model_import.h"
#include <glm/mat3x3.hpp>
#include <algorithm>
#include <cstring>
#include <string>

namespace penumbra {

// Calls use(i, v) for each element i of an accessor, v its `span.components` values
// as doubles (normalised integers scaled to [0, 1]), one element at a time: the
// callers convert straight into the mesh's float arrays, with no copy of the whole
// accessor. accessorSpan has proven every byte inside its buffer. Non-finite floats
// are refused unless `keepNonFinite` (normals and tangents: judged by the caller).
template <class Use>
void forEachElement(const AccessorSpan& span, const std::string& where, const std::string& path, bool keepNonFinite,
                    Use&& use) {
  double v[16] = {};  // the widest accessor type, MAT4; zeros without a buffer view (the spec)
  const int components = std::min(span.components, 16);
  for (uint64_t i = 0; i < span.count; ++i) {
    const unsigned char* p = span.data ? span.data + i * span.stride : nullptr;
    for (int c = 0; p && c < components; ++c, p += span.componentSize) {
      switch (span.componentType) {
        case TINYGLTF_COMPONENT_TYPE_FLOAT: { float f; std::memcpy(&f, p, 4); v[c] = f; break; }
        case TINYGLTF_COMPONENT_TYPE_BYTE: { int8_t b; std::memcpy(&b, p, 1); v[c] = span.normalized ? std::max(b / 127.0, -1.0) : b; break; }
        case TINYGLTF_COMPONENT_TYPE_UNSIGNED_BYTE: v[c] = *p / (span.normalized ? 255.0 : 1.0); break;
        case TINYGLTF_COMPONENT_TYPE_SHORT: { int16_t h; std::memcpy(&h, p, 2); v[c] = span.normalized ? std::max(h / 32767.0, -1.0) : h; break; }
        case TINYGLTF_COMPONENT_TYPE_UNSIGNED_SHORT: { uint16_t h; std::memcpy(&h, p, 2); v[c] = h / (span.normalized ? 65535.0 : 1.0); break; }
        case TINYGLTF_COMPONENT_TYPE_UNSIGNED_INT: { uint32_t u; std::memcpy(&u, p, 4); v[c] = u; break; }
        default: gltfFail(path, where, "a component type penumbra does not read");
      }
      if (!keepNonFinite && !std::isfinite(v[c])) gltfFail(path, where, "holds a value that is not a finite float");
    }
    if (!use(size_t(i), static_cast<const double*>(v))) return;
  }
}

// TANGENT (VEC4 FLOAT: xyz along +u, w the bitangent's sign), read only for a
// normal-mapped primitive. The node's linear map carries xyz; a mirroring one turns w.
// A tangent that cannot be normalised leaves the primitive to computed tangents.
void addTangents(const tinygltf::Model& m, int accessor, const glm::dmat3& linear, const std::string& where,
                 const std::string& path, TriangleMesh& mesh, LoadedModel& out);

// COLOR_0 (VEC3 or VEC4 of FLOAT, or of normalised UNSIGNED_BYTE / UNSIGNED_SHORT, as
// checkGltfModel proved) as linear RGBA clamped to [0, 1]; VEC3 has alpha 1.
void addColors(const tinygltf::Model& m, int accessor, const std::string& where, const std::string& path,
               TriangleMesh& mesh);

}  // namespace penumbra
