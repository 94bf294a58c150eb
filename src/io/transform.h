// Object transforms (scale, then rotate X/Y/Z, then translate) and applying
// them to a TriangleMesh: positions, inverse-transpose normals and winding.
#pragma once
#include "core/scene.h"
#include <glm/mat3x3.hpp>

namespace penumbra {

class JsonNode;

struct Transform {
  Vec3 scale{1.0f};
  Vec3 rotateDegrees{0.0f};  // applied about X, then Y, then Z
  Vec3 translate{0.0f};

  bool isIdentity() const;
  glm::mat3 linear() const;  // R * S
};

// Reads the optional "translate", "rotate" and "scale" keys of an object node;
// scale is a number or [sx, sy, sz], every component non-zero.
Transform readTransform(const JsonNode& object);

// Transforms the mesh in place. Normals use the inverse transpose and are
// renormalised; a mirroring transform (negative determinant) flips every
// triangle's winding so the geometric normal keeps pointing outwards.
void applyTransform(const Transform& transform, TriangleMesh& mesh);

}  // namespace penumbra
