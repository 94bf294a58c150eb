// libFuzzer target for the OBJ path: bytes -> a file loadObj reads (it takes a
// path, not a stream), then the mesh invariants loadObj documents.
// Input: OBJ text, optionally followed by "\n#mtl\n" and the text of fuzz.mtl.
#include "io/obj_loader.h"

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

// RAM-backed when possible: on ext4, rewriting a truncated file flushes it on
// close (auto_da_alloc), which cut the run to ~200 inputs/s.
fs::path scratchRoot() {
  std::error_code ec;
  if (std::getenv("TMPDIR") == nullptr && fs::is_directory("/dev/shm", ec)) return "/dev/shm";
  return fs::temp_directory_path();
}

// One private folder per process (libFuzzer -jobs/-fork run several at once),
// removed at exit. Files are unlinked and recreated, never truncated in place.
class Scratch {
 public:
  Scratch() {
    std::string pattern = (scratchRoot() / "penumbra_fuzz_obj.XXXXXX").string();
    if (!mkdtemp(pattern.data())) {
      std::perror("fuzz_obj_loader: mkdtemp");
      std::abort();
    }
    dir_ = pattern;
  }
  ~Scratch() {
    std::error_code ec;
    fs::remove_all(dir_, ec);
  }
  std::string write(const char* name, const std::string& text) const {
    std::string path = (dir_ / name).string();
    ::unlink(path.c_str());
    std::ofstream out(path, std::ios::binary);
    out.write(text.data(), static_cast<std::streamsize>(text.size()));
    if (!out) {
      std::fprintf(stderr, "fuzz_obj_loader: cannot write %s\n", path.c_str());
      std::abort();
    }
    return path;
  }

 private:
  fs::path dir_;
};

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
