// Meshes as solids: whether a mesh bounds a volume (edge-manifold and consistently
// wound), whether a point lies inside it, and the volume it encloses.
#pragma once
#include <cmath>
#include "core/scene.h"
#include <cstdint>

namespace penumbra {

// Edges (vertices welded by exact position) not shared by exactly two triangles of
// opposite orientation, degenerate ones included: 0 for a closed mesh.
uint64_t openEdgeCount(const TriangleMesh& mesh);

// Whether `p` lies inside a closed mesh: the parity of a ray's crossings, voted over
// three skew rays so one grazing an edge cannot decide alone.
bool meshContains(const TriangleMesh& mesh, const Vec3& p);

// The volume a closed mesh encloses (the divergence theorem over its triangles):
// negative when its triangles are wound inwards.
double signedVolume(const TriangleMesh& mesh);
inline double enclosedVolume(const TriangleMesh& mesh) { return std::abs(signedVolume(mesh)); }

}  // namespace penumbra
