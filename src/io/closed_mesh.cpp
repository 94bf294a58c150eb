// Closedness by welded directed edges, containment by ray parity in double precision:
// both run at load, and only for scenes with media.
#include "io/closed_mesh.h"

#include <algorithm>
#include <cmath>
#include <cstring>
#include <unordered_map>
#include <vector>

namespace penumbra {

namespace {

struct PositionHash {
  size_t operator()(const Vec3& p) const {
    uint32_t b[3];
    std::memcpy(b, &p, sizeof b);
    return (size_t(b[0]) * 0x9E3779B97F4A7C15ull) ^ (size_t(b[1]) * 0xC2B2AE3D27D4EB4Full) ^ b[2];
  }
};

// Each vertex's id after welding equal positions: a box's faces, or a model's
// per-face vertices, share corners only by position.
std::vector<uint32_t> weldedIds(const TriangleMesh& mesh) {
  std::unordered_map<Vec3, uint32_t, PositionHash> ids;
  ids.reserve(mesh.positions.size());
  std::vector<uint32_t> out(mesh.positions.size());
  for (size_t i = 0; i < mesh.positions.size(); ++i) {
    // -0 and 0 are one position.
    const Vec3 p = mesh.positions[i] + Vec3(0.0f);
    out[i] = ids.emplace(p, static_cast<uint32_t>(ids.size())).first->second;
  }
  return out;
}

// Crossings of the ray p + t d (t > 0) with the mesh's triangles (Möller–Trumbore).
int crossings(const TriangleMesh& mesh, const glm::dvec3& p, const glm::dvec3& d) {
  int n = 0;
  for (const auto& tri : mesh.triangles) {
    const glm::dvec3 a(mesh.positions[tri[0]]), b(mesh.positions[tri[1]]), c(mesh.positions[tri[2]]);
    const glm::dvec3 e1 = b - a, e2 = c - a, q = glm::cross(d, e2);
    const double det = glm::dot(e1, q);
    if (det == 0.0) continue;
    const glm::dvec3 s = p - a;
    const double u = glm::dot(s, q) / det;
    if (u < 0.0 || u > 1.0) continue;
    const glm::dvec3 r = glm::cross(s, e1);
    const double v = glm::dot(d, r) / det;
    if (v < 0.0 || u + v > 1.0) continue;
    if (glm::dot(e2, r) / det > 0.0) ++n;
  }
  return n;
}

}  // namespace

uint64_t openEdgeCount(const TriangleMesh& mesh) {
  const std::vector<uint32_t> id = weldedIds(mesh);
  std::vector<uint64_t> directed;
  directed.reserve(mesh.triangles.size() * 3);
  uint64_t open = 0;
  for (const auto& tri : mesh.triangles) {
    for (int e = 0; e < 3; ++e) {
      const uint32_t a = id[tri[e]], b = id[tri[(e + 1) % 3]];
      if (a == b) {
        ++open;  // a collapsed edge bounds nothing
        continue;
      }
      directed.push_back(uint64_t(a) << 32 | b);
    }
  }
  std::sort(directed.begin(), directed.end());
  // Closed: each directed edge exactly once, and its reverse exactly once.
  for (size_t i = 0; i < directed.size(); ++i) {
    const bool repeated = (i > 0 && directed[i - 1] == directed[i]) ||
                          (i + 1 < directed.size() && directed[i + 1] == directed[i]);
    const uint64_t reverse = directed[i] << 32 | directed[i] >> 32;
    if (repeated || !std::binary_search(directed.begin(), directed.end(), reverse)) ++open;
  }
  return open;
}

bool meshContains(const TriangleMesh& mesh, const Vec3& p) {
  // Skew directions: no axis-aligned face, edge or diagonal lies along them.
  static const glm::dvec3 kDirections[3] = {glm::normalize(glm::dvec3(0.5377, 0.8291, 0.1534)),
                                            glm::normalize(glm::dvec3(-0.6713, 0.2467, 0.6990)),
                                            glm::normalize(glm::dvec3(0.3191, -0.7719, 0.5497))};
  int inside = 0;
  for (const glm::dvec3& d : kDirections) inside += crossings(mesh, glm::dvec3(p), d) % 2;
  return inside >= 2;
}

double signedVolume(const TriangleMesh& mesh) {
  double six = 0.0;
  for (const auto& tri : mesh.triangles) {
    const glm::dvec3 a(mesh.positions[tri[0]]), b(mesh.positions[tri[1]]), c(mesh.positions[tri[2]]);
    six += glm::dot(a, glm::cross(b, c));
  }
  return six / 6.0;
}

}  // namespace penumbra
