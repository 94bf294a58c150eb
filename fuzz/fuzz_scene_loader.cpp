// libFuzzer target for the scene loader: JSON text plus --set overrides through
// parseScene, then the invariants the render stages rely on for a loaded Scene.
// Input: scene JSON, optionally followed by "\n#set\n" and one override per line.
#include "core/error.h"
#include "core/scene.h"
#include "io/scene_loader.h"
#include "fuzz_media_checks.h"

#include <cmath>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <string>
#include <vector>

namespace {

// Can never occur in valid JSON (a raw newline is not allowed inside a string),
// so splitting on it loses nothing the JSON parser could accept.
constexpr const char kSetMarker[] = "\n#set\n";
// More overrides add no new code paths, only time per input.
constexpr size_t kMaxOverrides = 8;

// The scene file name the loader sees: relative "file" keys resolve against
// tests/data, so seeds can name its small OBJ files (quad_normals.obj, ...).
const std::string kSceneFile = std::string(PENUMBRA_SOURCE_DIR) + "/tests/data/fuzz.json";

// A teapot costs subdivisions^2 patches: 64 takes ~3 s under ASan, which would
// turn every mutation of one seed into a timeout report. Inputs asking for more
// than kMaxSubdivisions, or more than kMaxTeapots of them, are skipped (a cost
// cap on raw text, not a parser: escapes can slip past, and that only costs time).
constexpr long kMaxSubdivisions = 8;
constexpr size_t kMaxTeapots = 2;

bool tooExpensive(const std::string& input) {
  size_t teapots = 0;
  for (size_t at = input.find("teapot"); at != std::string::npos; at = input.find("teapot", at + 1)) {
    if (++teapots > kMaxTeapots) return true;
  }
  const std::string key = "subdivisions";
  for (size_t at = input.find(key); at != std::string::npos; at = input.find(key, at + 1)) {
    size_t i = at + key.size();
    while (i < input.size() && (input[i] == '"' || input[i] == ':' || input[i] == '=' ||
                                input[i] == ' ' || input[i] == '\t' || input[i] == '\n')) {
      ++i;
    }
    long value = 0;
    while (i < input.size() && input[i] >= '0' && input[i] <= '9' && value <= kMaxSubdivisions) {
      value = value * 10 + (input[i++] - '0');
    }
    if (value > kMaxSubdivisions) return true;
  }
  return false;
}

// A broken invariant is a finding: say which, then abort so libFuzzer saves the input.
[[noreturn]] void broken(const char* what) {
  std::fprintf(stderr, "fuzz_scene_loader: invariant broken: %s\n", what);
  std::abort();
}

bool finite(const penumbra::Vec3& v) {
  return std::isfinite(v.x) && std::isfinite(v.y) && std::isfinite(v.z);
}

// What a Scene that parseScene returned must satisfy: every index it holds is in
// range and the geometry is finite, or a later stage reads out of bounds or NaN.
void checkScene(const penumbra::Scene& scene) {
  const int numMaterials = static_cast<int>(scene.materials.size());
  const int numTextures = static_cast<int>(scene.textures.size());
  const int numLights = static_cast<int>(scene.lights.size());
  for (const penumbra::Material& m : scene.materials) {
    if (m.texture < -1 || m.texture >= numTextures) broken("material texture index out of range");
    if (m.light < -1 || m.light >= numLights) broken("material light index out of range");
    if (!(m.pR >= 0.0f && m.pT >= 0.0f && m.pR + m.pT <= 1.0f + 1e-5f)) {
      broken("photon probabilities outside [0, 1]");
    }
  }
  for (const penumbra::Sphere& s : scene.spheres) {
    if (s.material < 0 || s.material >= numMaterials) broken("sphere material out of range");
    if (!finite(s.center) || !(s.radius > 0.0f) || !std::isfinite(s.radius)) {
      broken("sphere centre or radius not finite and positive");
    }
  }
  for (const penumbra::TriangleMesh& mesh : scene.meshes) {
    if (mesh.material < 0 || mesh.material >= numMaterials) broken("mesh material out of range");
    if (mesh.triangles.empty()) broken("a mesh without triangles");
    const size_t n = mesh.positions.size();
    if (!mesh.normals.empty() && mesh.normals.size() != n) broken("normals count != positions");
    if (!mesh.uvs.empty() && mesh.uvs.size() != n) broken("uvs count != positions");
    for (const auto& tri : mesh.triangles) {
      for (uint32_t i : tri) {
        if (i >= n) broken("triangle index out of range");
      }
    }
    for (const penumbra::Vec3& p : mesh.positions) {
      if (!finite(p)) broken("mesh position not finite");
    }
    for (const penumbra::Vec3& nrm : mesh.normals) {
      if (!finite(nrm)) broken("mesh normal not finite");
    }
  }
  for (const penumbra::Light& light : scene.lights) {
    if (!finite(light.position) || !finite(light.direction) || !std::isfinite(light.intensity)) {
      broken("light position, direction or intensity not finite");
    }
  }
  const penumbra::Camera& c = scene.camera;
  if (c.width <= 0 || c.height <= 0 || c.spp <= 0) broken("camera size or spp not positive");
  if (!finite(c.position) || !finite(c.lookAt) || !finite(c.up) || !std::isfinite(c.fovY)) {
    broken("camera not finite");
  }
  penumbra_fuzz::checkMedia(scene);
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  const std::string input(reinterpret_cast<const char*>(data), size);
  if (tooExpensive(input)) return -1;  // -1: libFuzzer keeps it out of the corpus
  std::string json = input;
  std::vector<std::string> overrides;
  const size_t marker = input.find(kSetMarker);
  if (marker != std::string::npos) {
    json = input.substr(0, marker);
    size_t pos = marker + sizeof(kSetMarker) - 1;
    while (pos <= input.size() && overrides.size() < kMaxOverrides) {
      size_t end = input.find('\n', pos);
      if (end == std::string::npos) end = input.size();
      overrides.push_back(input.substr(pos, end - pos));
      pos = end + 1;
    }
  }
  try {
    checkScene(penumbra::parseScene(json, kSceneFile, overrides));
  } catch (const penumbra::InputError&) {
    // The documented way to reject input. Anything else escaping is a finding:
    // libFuzzer reports the uncaught exception's abort as a crash.
  }
  return 0;
}
