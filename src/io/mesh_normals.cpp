// Angle-weighted vertex normal accumulation (used by the OBJ loader).
#include "io/mesh_normals.h"

namespace penumbra {

namespace {

// Angle between two vectors via atan2, which stays accurate near 0 and pi where
// acos of a dot product loses most of its digits.
double angleBetween(const glm::dvec3& a, const glm::dvec3& b) {
  return std::atan2(glm::length(glm::cross(a, b)), glm::dot(a, b));
}

}  // namespace

std::vector<Vec3> angleWeightedNormals(const std::vector<Vec3>& positions,
                                       const std::vector<std::array<uint32_t, 3>>& triangles) {
  // Double precision: thousands of small contributions are summed per vertex.
  std::vector<glm::dvec3> sums(positions.size(), glm::dvec3(0.0));
  for (const auto& tri : triangles) {
    glm::dvec3 p[3];
    for (int k = 0; k < 3; ++k) p[k] = glm::dvec3(positions[tri[k]]);
    glm::dvec3 faceNormal = glm::cross(p[1] - p[0], p[2] - p[0]);
    double area2 = glm::length(faceNormal);
    if (!(area2 > 0.0) || !std::isfinite(area2)) continue;  // degenerate face
    faceNormal /= area2;
    for (int k = 0; k < 3; ++k) {
      glm::dvec3 toNext = p[(k + 1) % 3] - p[k];
      glm::dvec3 toPrev = p[(k + 2) % 3] - p[k];
      sums[tri[k]] += faceNormal * angleBetween(toNext, toPrev);
    }
  }
  std::vector<Vec3> normals(positions.size());
  for (size_t i = 0; i < sums.size(); ++i) {
    double len = glm::length(sums[i]);
    normals[i] = len > 1e-12 ? Vec3(sums[i] / len) : Vec3(0.0f, 0.0f, 1.0f);
  }
  return normals;
}

}  // namespace penumbra
