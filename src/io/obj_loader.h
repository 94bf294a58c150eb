// Wavefront OBJ files to TriangleMesh via tinyobjloader, with their MTL materials.
#pragma once
#include "core/scene.h"
#include "io/model_import.h"
#include <string>

namespace penumbra {

// Why an OBJ file could not be used; the scene loader adds the scene file and
// JSON path in front of the message.
class ObjError : public ModelError {
 public:
  using ModelError::ModelError;
};

// Loads `path` (triangulating polygons) into one mesh named after the file stem.
// Vertices are unified per distinct (position, normal, uv) index triple. The
// file's normals are used (renormalised) when every face corner has one;
// otherwise angle-weighted smooth normals are computed over shared positions.
// UVs are kept, unflipped, when every corner has one. Throws ObjError for a
// missing or unparsable file, out-of-range indices, a v/vn/vt field that is not
// a finite float (with its line: tinyobjloader would read "nan" as 0) or a file
// without triangles.
TriangleMesh loadObj(const std::string& path);

// The same file as one mesh per `usemtl` material (in order of first use; faces
// without one form a mesh with material -1), each with its own vertices, and the
// MTL materials mapped onto penumbra's: Kd, Ks, Ns, Ni, d/Tr (glass), Tf (tint),
// illum 3/5 (mirror), Ke (emission; Ka above 1 without Ke counts as emission),
// map_Kd (a texture path resolved against the OBJ's folder).
LoadedModel loadObjModel(const std::string& path, const LoadLimits& limits = {});

}  // namespace penumbra
