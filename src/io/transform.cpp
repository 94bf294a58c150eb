// Scale-rotate-translate transforms for meshes, quads, boxes and teapots.
#include "io/transform.h"

#include "io/json_reader.h"

#include <cmath>
#include <glm/matrix.hpp>
#include <utility>

namespace penumbra {

namespace {

// Rotation about one axis (0 = X, 1 = Y, 2 = Z), right-handed. Whole multiples
// of 90 degrees use exact cosines and sines so a right-angle turn maps axes onto
// axes instead of leaving 1e-8 residue in the other coordinates.
glm::mat3 axisRotation(int axis, float degrees) {
  float r = glm::radians(degrees);
  float c = std::cos(r), s = std::sin(r);
  double turns = static_cast<double>(degrees) / 90.0;
  if (turns == std::floor(turns)) {
    int q = static_cast<int>(std::fmod(std::fmod(turns, 4.0) + 4.0, 4.0));
    const float cs[4] = {1, 0, -1, 0}, sn[4] = {0, 1, 0, -1};
    c = cs[q];
    s = sn[q];
  }
  // glm is column-major: each Vec3 below is a column, the image of an axis.
  if (axis == 0) return glm::mat3(Vec3(1, 0, 0), Vec3(0, c, s), Vec3(0, -s, c));
  if (axis == 1) return glm::mat3(Vec3(c, 0, -s), Vec3(0, 1, 0), Vec3(s, 0, c));
  return glm::mat3(Vec3(c, s, 0), Vec3(-s, c, 0), Vec3(0, 0, 1));
}

}  // namespace

bool Transform::isIdentity() const {
  return scale == Vec3(1.0f) && rotateDegrees == Vec3(0.0f) && translate == Vec3(0.0f);
}

glm::mat3 Transform::linear() const {
  glm::mat3 s(Vec3(scale.x, 0, 0), Vec3(0, scale.y, 0), Vec3(0, 0, scale.z));
  glm::mat3 r = axisRotation(2, rotateDegrees.z) * axisRotation(1, rotateDegrees.y) *
                axisRotation(0, rotateDegrees.x);
  return r * s;
}

Transform readTransform(const JsonNode& object) {
  Transform t;
  t.translate = object.vec3Or("translate", t.translate);
  t.rotateDegrees = object.vec3Or("rotate", t.rotateDegrees);
  if (object.has("scale")) {
    JsonNode s = object.child("scale");
    t.scale = s.value().is_number() ? Vec3(s.asFloat()) : s.asVec3();
    if (t.scale.x == 0.0f || t.scale.y == 0.0f || t.scale.z == 0.0f) {
      s.fail("must be non-zero on every axis");
    }
  }
  return t;
}

void applyTransform(const Transform& transform, TriangleMesh& mesh) {
  if (transform.isIdentity()) return;
  glm::mat3 m = transform.linear();
  for (Vec3& p : mesh.positions) p = m * p + transform.translate;
  if (!mesh.normals.empty()) {
    glm::mat3 normalMatrix = glm::transpose(glm::inverse(m));
    for (Vec3& n : mesh.normals) {
      Vec3 t = normalMatrix * n;
      float len = glm::length(t);
      n = len > 0.0f ? t / len : n;
    }
  }
  // Tangents are directions in the surface: they follow the linear map; a mirror
  // turns the bitangent's handedness with the winding.
  const float handedness = glm::determinant(m) < 0.0f ? -1.0f : 1.0f;
  for (glm::vec4& t : mesh.tangents) {
    const Vec3 d = m * Vec3(t);
    const float len = glm::length(d);
    t = glm::vec4(len > 0.0f ? d / len : Vec3(t), t.w * handedness);
  }
  if (glm::determinant(m) < 0.0f) {
    for (auto& tri : mesh.triangles) std::swap(tri[1], tri[2]);
  }
}

}  // namespace penumbra
