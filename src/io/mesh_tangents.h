// Per-vertex tangents for normal-mapped meshes, computed at load from positions and
// uvs when the file gives none (MikkTSpace in spirit: per-triangle uv derivatives,
// accumulated per vertex, made orthogonal to the vertex normal).
#pragma once
#include "core/scene.h"

namespace penumbra {

// Fills mesh.tangents (one per vertex, xyz unit and orthogonal to the vertex normal,
// w = +-1 so that cross(n, t) x w points up the image, towards -v). A mesh without
// uvs, or a vertex whose triangles give no uv direction, gets a tangent from the
// normal alone (orthonormalBasis), w = 1.
void computeTangents(TriangleMesh& mesh);

// Every mesh whose material has a normal map and no tangents yet gets them; the
// others keep an empty tangent list (no memory for scenes without normal maps).
void addMissingTangents(Scene& scene);

}  // namespace penumbra
