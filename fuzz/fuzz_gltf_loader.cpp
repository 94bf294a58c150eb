// libFuzzer target for the glTF path: bytes -> a .glb (if they start with the
// binary magic) or a .gltf file that loadScene reads as a whole scene, then the
// invariants every loaded scene keeps. The parser is Debian's tinygltf (built
// without coverage), so the fuzzer mostly steers penumbra's mapping of its result
// onto meshes, materials, cameras and lights, and the checks penumbra makes before
// tinygltf sees the bytes (nesting, versions, buffer bounds, URIs).
#include "core/error.h"
#include "fuzz_scratch.h"
#include "io/load_limits.h"
#include "io/scene_loader.h"

#include <cmath>
#include <cstdint>
#include <cstring>

namespace {

[[noreturn]] void broken(const char* what) {
  std::fprintf(stderr, "fuzz_gltf_loader: invariant broken: %s\n", what);
  std::abort();
}

bool finite(const penumbra::Vec3& v) { return std::isfinite(v.x) && std::isfinite(v.y) && std::isfinite(v.z); }

// What the loader promises of any scene it returns (scene_loader.h, float_checks.h).
void checkScene(const penumbra::Scene& scene) {
  const size_t materials = scene.materials.size();
  for (const penumbra::TriangleMesh& m : scene.meshes) {
    if (m.material < 0 || static_cast<size_t>(m.material) >= materials) broken("mesh material out of range");
    for (const auto& tri : m.triangles) {
      for (uint32_t i : tri) {
        if (i >= m.positions.size()) broken("triangle index out of range");
      }
    }
    for (const penumbra::Vec3& p : m.positions) {
      if (!finite(p)) broken("position not finite");
    }
  }
  for (const penumbra::Light& l : scene.lights) {
    if (!finite(l.position) || !std::isfinite(l.intensity)) broken("light not finite");
  }
  if (!finite(scene.camera.position) || !finite(scene.camera.lookAt)) broken("camera not finite");
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  static const penumbra_fuzz::Scratch scratch;
  const std::string input(reinterpret_cast<const char*>(data), size);
  const bool binary = size >= 4 && std::memcmp(data, "glTF", 4) == 0;
  const std::string path = scratch.write(binary ? "fuzz.glb" : "fuzz.gltf", input);
  try {
    // A budget, as the CLI always has one: the loader's estimate refuses what would
    // exceed it, so a small input can no longer ask for gigabytes.
    checkScene(penumbra::loadScene(path, {}, penumbra::LoadLimits{512ull << 20, "the fuzzer's budget"}));
  } catch (const penumbra::InputError&) {
    // The loader's documented rejection; anything else escaping is a finding.
  }
  return 0;
}
