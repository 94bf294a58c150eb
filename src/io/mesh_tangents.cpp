// Tangents from uvs: each triangle's dP/du and dP/dv (Lengyel's solve), unit length,
// summed at its corners weighted by the corner's angle as MikkTSpace weights them,
// then made orthogonal to the vertex normal with the bitangent's sign kept in w.
#include "io/mesh_tangents.h"
#include "io/mesh_normals.h"

#include <cmath>

namespace penumbra {

namespace {

double cornerAngle(const glm::dvec3& a, const glm::dvec3& b) {
  const double la = glm::length(a), lb = glm::length(b);
  if (!(la > 0.0) || !(lb > 0.0)) return 0.0;
  return std::acos(std::clamp(glm::dot(a, b) / (la * lb), -1.0, 1.0));
}

glm::dvec3 unitOrZero(const glm::dvec3& v) {
  const double len = glm::length(v);
  return len > 0.0 && std::isfinite(len) ? v / len : glm::dvec3(0.0);
}

}  // namespace

void computeTangents(TriangleMesh& mesh) {
  const size_t n = mesh.positions.size();
  // Per vertex, the angle-weighted sums of the triangles' unit dP/du and dP/dv.
  std::vector<glm::dvec3> du(n, glm::dvec3(0.0)), dv(n, glm::dvec3(0.0));
  const bool uvs = mesh.uvs.size() == n;
  for (const auto& tri : mesh.triangles) {
    if (!uvs) break;
    const glm::dvec3 p0(mesh.positions[tri[0]]), p1(mesh.positions[tri[1]]), p2(mesh.positions[tri[2]]);
    const glm::dvec2 t0(mesh.uvs[tri[0]]), t1(mesh.uvs[tri[1]]), t2(mesh.uvs[tri[2]]);
    const glm::dvec3 e1 = p1 - p0, e2 = p2 - p0;
    const glm::dvec2 s1 = t1 - t0, s2 = t2 - t0;
    const double det = s1.x * s2.y - s2.x * s1.y;
    if (!(std::fabs(det) > 0.0) || !std::isfinite(det)) continue;  // no uv area: no direction
    // P - p0 = e1 a + e2 b with (u, v) - t0 = s1 a + s2 b: solve for dP/du and dP/dv.
    const glm::dvec3 tu = unitOrZero((e1 * s2.y - e2 * s1.y) / det);
    const glm::dvec3 tv = unitOrZero((e2 * s1.x - e1 * s2.x) / det);
    const glm::dvec3 corners[3] = {p0, p1, p2};
    for (int k = 0; k < 3; ++k) {
      const double w = cornerAngle(corners[(k + 1) % 3] - corners[k], corners[(k + 2) % 3] - corners[k]);
      du[tri[k]] += w * tu;
      dv[tri[k]] += w * tv;
    }
  }
  // The normal each tangent is made orthogonal to: the vertex normal the shading
  // interpolates, or for a flat-shaded mesh the angle-weighted face normals.
  const std::vector<Vec3> normals =
      mesh.normals.size() == n ? mesh.normals : angleWeightedNormals(mesh.positions, mesh.triangles);
  mesh.tangents.assign(n, glm::vec4(1.0f, 0.0f, 0.0f, 1.0f));
  for (size_t i = 0; i < n; ++i) {
    const glm::dvec3 normal(normals[i]);
    const glm::dvec3 t = unitOrZero(du[i] - normal * glm::dot(normal, du[i]));
    if (t == glm::dvec3(0.0)) {
      // No uv direction here: any frame around the normal (a constant map still tilts).
      Vec3 tangent, bitangent;
      orthonormalBasis(normals[i], tangent, bitangent);
      mesh.tangents[i] = glm::vec4(tangent, 1.0f);
      continue;
    }
    // The image's up is -v (row 0 at the top): the bitangent cross(n, t) w points there.
    const double w = glm::dot(glm::cross(normal, t), -dv[i]) < 0.0 ? -1.0 : 1.0;
    mesh.tangents[i] = glm::vec4(Vec3(t), float(w));
  }
}

void addMissingTangents(Scene& scene) {
  for (size_t i = 0; i < scene.meshes.size(); ++i) {
    const TriangleMesh& mesh = scene.meshes[i];
    const bool mapped = mesh.material >= 0 && static_cast<size_t>(mesh.material) < scene.materials.size() &&
                        scene.materials[mesh.material].normalTexture >= 0;
    if (mapped && mesh.tangents.size() != mesh.positions.size()) {
      computeTangents(scene.meshes[i]);
    } else if (!mapped && !mesh.tangents.empty()) {
      scene.meshes[i].tangents = {};  // a file's tangents no normal map reads
    }
  }
}

}  // namespace penumbra
