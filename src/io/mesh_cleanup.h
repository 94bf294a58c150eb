// Removes triangles the tracer cannot shade: a zero or underflowing float cross
// product has no normal, and a NaN normal poisons every ray offset after it.
#pragma once
#include "core/scene.h"

namespace penumbra {

// Drops those triangles in place, keeping the order of the rest; returns how many.
size_t dropDegenerateTriangles(TriangleMesh& mesh);

}  // namespace penumbra
