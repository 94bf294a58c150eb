// Degenerate-triangle and white-colour removal for loaded and transformed meshes.
#include "io/mesh_cleanup.h"
#include <algorithm>

namespace penumbra {

size_t dropDegenerateTriangles(TriangleMesh& mesh) {
  const size_t before = mesh.triangles.size();
  auto degenerate = [&](const std::array<uint32_t, 3>& t) {
    const Vec3 &a = mesh.positions[t[0]], &b = mesh.positions[t[1]], &c = mesh.positions[t[2]];
    Vec3 n = glm::cross(b - a, c - a);
    float len2 = glm::dot(n, n);
    // The tracer normalises this vector (unitCross): it must be non-zero with a
    // normal-range square; a square that overflows float is taken in double.
    if (std::isinf(len2)) return !isFinite(n) || !(glm::length(glm::cross(glm::dvec3(b - a), glm::dvec3(c - a))) > 0.0);
    return !(len2 >= std::numeric_limits<float>::min()) || !std::isfinite(len2);
  };
  mesh.triangles.erase(std::remove_if(mesh.triangles.begin(), mesh.triangles.end(), degenerate),
                       mesh.triangles.end());
  return before - mesh.triangles.size();
}

void dropWhiteColors(TriangleMesh& mesh) {
  const auto white = [](const glm::vec4& c) { return c == glm::vec4(1.0f); };
  if (!std::all_of(mesh.colors.begin(), mesh.colors.end(), white)) return;
  mesh.colors.clear();
  mesh.colors.shrink_to_fit();
}

}  // namespace penumbra
