// libFuzzer target for the OBJ path: bytes -> a file loadObj reads (it takes a
// path, not a stream), then the mesh invariants loadObj documents.
// Input: OBJ text, optionally followed by "\n#mtl\n" and the text of fuzz.mtl.
#include "io/obj_loader.h"
#include "fuzz_scratch.h"

#include <unistd.h>

#include <cmath>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <string>

namespace {

namespace fs = std::filesystem;

// "mtllib fuzz.mtl" in the OBJ part loads the second part: tinyobjloader's
// material parser is on loadObj's path too.
constexpr const char kMtlMarker[] = "\n#mtl\n";

using penumbra_fuzz::Scratch;

[[noreturn]] void broken(const char* what) {
  std::fprintf(stderr, "fuzz_obj_loader: invariant broken: %s\n", what);
  std::abort();
}

bool finite(const penumbra::Vec3& v) {
  return std::isfinite(v.x) && std::isfinite(v.y) && std::isfinite(v.z);
}

// obj_loader.h: triangles index real vertices, positions are finite, normals are
// per vertex and unit length, uvs are per vertex or absent.
void checkMesh(const penumbra::TriangleMesh& mesh) {
  const size_t n = mesh.positions.size();
  if (mesh.triangles.empty()) broken("a mesh without triangles");
  if (mesh.normals.size() != n) broken("normals count != positions count");
  if (!mesh.uvs.empty() && mesh.uvs.size() != n) broken("uvs count != positions count");
  for (const auto& tri : mesh.triangles) {
    for (uint32_t i : tri) {
      if (i >= n) broken("triangle index out of range");
    }
  }
  for (const penumbra::Vec3& p : mesh.positions) {
    if (!finite(p)) broken("position not finite");
  }
  for (const penumbra::Vec3& nrm : mesh.normals) {
    float len = std::sqrt(nrm.x * nrm.x + nrm.y * nrm.y + nrm.z * nrm.z);
    if (!(std::fabs(len - 1.0f) < 1e-3f)) broken("normal not unit length (or not finite)");
  }
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  static const Scratch scratch;
  const std::string input(reinterpret_cast<const char*>(data), size);
  const size_t marker = input.find(kMtlMarker);
  // Always write the .mtl, so an input without one does not see the last one's.
  scratch.write("fuzz.mtl",
                marker == std::string::npos ? std::string() : input.substr(marker + sizeof(kMtlMarker) - 1));
  const std::string path = scratch.write("mesh.obj", input.substr(0, marker));
  try {
    checkMesh(penumbra::loadObj(path));
  } catch (const penumbra::ObjError&) {
    // loadObj's documented rejection; anything else escaping is a finding.
  }
  return 0;
}
