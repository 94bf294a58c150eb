// Wavefront OBJ files to TriangleMesh via tinyobjloader.
#pragma once
#include "core/scene.h"
#include <stdexcept>
#include <string>

namespace penumbra {

// Why an OBJ file could not be used; the scene loader adds the scene file and
// JSON path in front of the message.
class ObjError : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
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

}  // namespace penumbra
