// Built-in shapes as triangle meshes: the axis-aligned box (the quad, makeQuad, is the
// quad light's surface too: core/lights/quad_light.h).
#pragma once
#include "core/scene.h"

namespace penumbra {

// The box [min, max] as 8 shared corners and 12 triangles, each counter-clockwise
// seen from outside so geometric normals face out. Flat: no normals, no uvs.
TriangleMesh makeBox(const Vec3& min, const Vec3& max, int material = 0);

}  // namespace penumbra
