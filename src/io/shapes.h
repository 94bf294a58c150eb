// Built-in shapes as triangle meshes: the quad and the axis-aligned box.
#pragma once
#include "core/scene.h"

namespace penumbra {

// Parallelogram corner, corner+edge1, corner+edge1+edge2, corner+edge2 as two
// triangles wound so the geometric normal is normalize(cross(edge1, edge2));
// that normal is also stored per vertex, and uvs run (0,0) (1,0) (1,1) (0,1).
// The edges must be non-zero and not parallel (the caller checks).
TriangleMesh makeQuad(const Vec3& corner, const Vec3& edge1, const Vec3& edge2, int material = 0);

// The box [min, max] as 8 shared corners and 12 triangles, each counter-clockwise
// seen from outside so geometric normals face out. Flat: no normals, no uvs.
TriangleMesh makeBox(const Vec3& min, const Vec3& max, int material = 0);

}  // namespace penumbra
