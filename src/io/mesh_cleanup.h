// Removes what a loaded mesh cannot use: triangles the tracer cannot shade (a zero
// or underflowing float cross product has no normal, and a NaN normal poisons every
// ray offset after it), and vertex colours that change nothing.
#pragma once
#include "core/scene.h"

namespace penumbra {

// Drops those triangles in place, keeping the order of the rest; returns how many.
size_t dropDegenerateTriangles(TriangleMesh& mesh);

// Frees colours that are all opaque white (exporters often write them): the mesh then
// shades as one without colours, at no memory or per-hit cost.
void dropWhiteColors(TriangleMesh& mesh);

}  // namespace penumbra
