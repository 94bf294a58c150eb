// Smooth vertex normals for meshes that come without any.
#pragma once
#include "core/math.h"
#include <array>
#include <cstdint>
#include <vector>

namespace penumbra {

// One unit normal per position: the sum of the normals of the faces around it,
// each weighted by the face's angle at that corner (Thuermer & Wuethrich 1998),
// so the result does not depend on how a surface happens to be triangulated.
// Degenerate faces are skipped; a position no usable face touches (or whose
// faces cancel out) gets +Z. Faces are counter-clockwise for an outward normal.
std::vector<Vec3> angleWeightedNormals(const std::vector<Vec3>& positions,
                                       const std::vector<std::array<uint32_t, 3>>& triangles);

}  // namespace penumbra
