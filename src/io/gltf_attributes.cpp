// TANGENT and COLOR_0 into a mesh: the per-vertex attributes a glTF primitive may
// carry beyond its positions, normals and uvs.
#include "io/gltf_attributes.h"
#include "io/float_checks.h"
#include <cmath>

namespace penumbra {

void addTangents(const tinygltf::Model& m, int accessor, const glm::dmat3& linear, const std::string& where,
                 const std::string& path, TriangleMesh& mesh, LoadedModel& out) {
  const AccessorSpan span = accessorSpan(m, accessor, where + ".attributes.TANGENT", path);
  if (span.components != 4 || span.componentType != TINYGLTF_COMPONENT_TYPE_FLOAT) {
    gltfFail(path, "accessors[" + std::to_string(accessor) + "]", "TANGENT must be a VEC4 of FLOAT");
  }
  if (span.count != mesh.positions.size()) {
    gltfFail(path, where + ".attributes.TANGENT", "has " + std::to_string(span.count) + " elements but POSITION has " +
                                                      std::to_string(mesh.positions.size()) + " (the spec wants equal counts)");
  }
  const double handedness = glm::determinant(linear) < 0.0 ? -1.0 : 1.0;
  mesh.tangents.reserve(span.count);
  forEachElement(span, where + ".attributes.TANGENT", path, true, [&](size_t, const double* t) {
    const Vec3 d(glm::normalize(linear * glm::dvec3(t[0], t[1], t[2])));
    if (!isFinite(d) || std::fabs(glm::length(d) - 1.0f) > 1e-3f || !std::isfinite(t[3])) {
      mesh.tangents.clear();
      mesh.tangents.shrink_to_fit();
      if (out.warning.empty()) out.warning = where + ".attributes.TANGENT: a tangent of zero length or not finite; tangents are computed from the uvs";
      return false;
    }
    mesh.tangents.emplace_back(d, t[3] * handedness < 0.0 ? -1.0f : 1.0f);
    return true;
  });
}

void addColors(const tinygltf::Model& m, int accessor, const std::string& where, const std::string& path,
               TriangleMesh& mesh) {
  const AccessorSpan span = accessorSpan(m, accessor, where + ".attributes.COLOR_0", path);
  mesh.colors.reserve(span.count);
  forEachElement(span, where + ".attributes.COLOR_0", path, false, [&](size_t, const double* c) {
    const float alpha = span.components == 4 ? float(c[3]) : 1.0f;
    mesh.colors.push_back(glm::clamp(glm::vec4(float(c[0]), float(c[1]), float(c[2]), alpha), 0.0f, 1.0f));
    return true;
  });
}

}  // namespace penumbra
