// What an OBJ and its MTL files hold, read line by line before tinyobjloader parses
// them: every number finite and in range (tinyobjloader reads "nan" or "inf" as 0),
// the MTL files the OBJ names, and the memory its vertices and faces will take.
#pragma once
#include "io/load_limits.h"
#include <cstdint>
#include <string>
#include <vector>

namespace penumbra {

struct ObjScan {
  std::vector<std::string> mtlFiles;  // mtllib files found, beside the OBJ or as given
  uint64_t positions = 0, normals = 0, uvs = 0, faceCorners = 0, faces = 0;
  uint64_t coloured = 0;  // `v` lines with a colour after the position (x y z r g b)
  // What loading allocates at its peak: tinyobjloader's arrays, the unified vertices
  // and the per-material copies.
  uint64_t loadBytes() const;
};

// Throws ObjError with the file and line for a v, vn or vt field that is not a finite
// float (or a texture coordinate beyond kMaxTexCoord), an mtllib not found, an MTL
// file too large to be one, an MTL value out of its range, or a file whose load would exceed `limits`.
ObjScan scanObj(const std::string& path, const LoadLimits& limits);

// The largest MTL file read: material libraries are text of a few kilobytes.
inline constexpr uint64_t kMaxMtlBytes = 16ull << 20;

}  // namespace penumbra
