// glTF cameras: each placed by the first node naming it, checked as the JSON camera
// is, and the choice among them by --camera (name or index), said in one line.
#include "io/gltf_cameras.h"

#include "core/error.h"
#include "io/camera_checks.h"
#include "io/gltf_checks.h"

#include <fmt/format.h>
#include <algorithm>
#include <cmath>

namespace penumbra {

namespace {

std::string label(const std::vector<GltfCamera>& cameras, size_t i) {
  const GltfCamera& c = cameras[i];
  std::string s = std::to_string(i);
  if (!c.name.empty()) s += " \"" + c.name + "\"";
  if (!c.nodeName.empty() && c.nodeName != c.name) s += " (node \"" + c.nodeName + "\")";
  if (c.order < 0) s += " (no node places it)";
  return s;
}

[[noreturn]] void refuse(const std::vector<GltfCamera>& cameras, const std::string& choice, const std::string& file,
                         const std::string& problem) {
  std::string line = fmt::format("{}: --camera {}: {}; ", file, choice, problem);
  if (cameras.empty()) throw InputError(line + "the file has no cameras (--camera auto frames the model)");
  line += "the file's cameras:";
  for (size_t i = 0; i < cameras.size(); ++i) line += (i ? ", " : " ") + label(cameras, i);
  throw InputError(line);
}

}  // namespace

std::vector<GltfCamera> gltfCameras(const tinygltf::Model& m) {
  std::vector<GltfCamera> out(m.cameras.size());
  for (size_t i = 0; i < out.size(); ++i) {
    out[i].name = m.cameras[i].name;
    out[i].used = m.cameras[i].type == "perspective" || m.cameras[i].type == "orthographic";
    const std::string where = "cameras[" + std::to_string(i) + "]";
    out[i].problem = out[i].used ? where + ": no node of the scene places it"
                                 : fmt::format("{}: only perspective and orthographic cameras are used, not \"{}\"",
                                               where, m.cameras[i].type);
  }
  return out;
}

void placeGltfCamera(const tinygltf::Model& m, int index, int node, const glm::dmat4& world, const std::string& path,
                     std::vector<GltfCamera>& cameras) {
  if (index < 0 || static_cast<size_t>(index) >= m.cameras.size()) {
    gltfFail(path, "nodes[" + std::to_string(node) + "].camera", "camera " + std::to_string(index) + " does not exist");
  }
  GltfCamera& out = cameras[index];
  if (out.order >= 0) return;
  out.order = static_cast<int>(
      std::count_if(cameras.begin(), cameras.end(), [](const GltfCamera& c) { return c.order >= 0; }));
  out.nodeName = m.nodes[node].name;
  const std::string camera = "cameras[" + std::to_string(index) + "]";
  if (!out.used) return;
  out.problem.clear();
  const tinygltf::Camera& g = m.cameras[index];
  Camera c;
  c.position = Vec3(world * glm::dvec4(0.0, 0.0, 0.0, 1.0));
  // One unit ahead, or more far from the origin, so look_at stays apart in float.
  const glm::dvec3 eye(world * glm::dvec4(0.0, 0.0, 0.0, 1.0)), ahead = glm::dmat3(world) * glm::dvec3(0.0, 0.0, -1.0);
  const double reach = std::max({1.0, std::fabs(eye.x), std::fabs(eye.y), std::fabs(eye.z)});
  c.lookAt = Vec3(eye + glm::normalize(ahead) * reach);
  c.up = Vec3(glm::normalize(glm::dmat3(world) * glm::dvec3(0.0, 1.0, 0.0)));
  double aspect = 0.0;
  if (g.type == "orthographic") {
    // xmag and ymag are half the view's width and height (positive: checkGltfModel).
    c.orthoHeight = static_cast<float>(2.0 * g.orthographic.ymag);
    aspect = g.orthographic.xmag / g.orthographic.ymag;
  } else {
    c.fovY = static_cast<float>(g.perspective.yfov * 180.0 / 3.14159265358979323846);
    aspect = g.perspective.aspectRatio;  // 0.01..100 (checkGltfModel), 0 = none
  }
  if (aspect > 0.0) {
    out.aspect = aspect;
    c.height = std::clamp(static_cast<int>(std::lround(c.width / aspect)), 1, 16384);
  }
  out.camera = c;
  // The node's transform places the camera: the JSON camera's checks apply here too.
  const CameraProblem problem = cameraProblem(c);
  if (problem.message.empty()) return;
  out.problem = problem.key == "ortho_height"
                    ? fmt::format("{}.orthographic.ymag (as placed by its node): {}", camera, problem.message)
                    : fmt::format("{} (as placed by its node): {}: {}", camera, problem.key, problem.message);
}

const GltfCamera* chooseGltfCamera(const std::vector<GltfCamera>& cameras, const std::string& choice,
                                   const std::string& file) {
  if (choice == "auto") return nullptr;
  const GltfCamera* chosen = nullptr;
  if (choice.empty()) {
    for (const GltfCamera& c : cameras) {
      if (c.used && c.order >= 0 && (!chosen || c.order < chosen->order)) chosen = &c;
    }
    if (!chosen) return nullptr;
  } else if (choice.find_first_not_of("0123456789") == std::string::npos) {
    const size_t index = choice.size() > 9 ? cameras.size() : std::stoul(choice);
    if (index >= cameras.size()) refuse(cameras, choice, file, "no camera " + choice);
    chosen = &cameras[index];
  } else {
    for (auto field : {&GltfCamera::name, &GltfCamera::nodeName}) {
      auto it = std::find_if(cameras.begin(), cameras.end(), [&](const GltfCamera& c) { return c.*field == choice; });
      if (!chosen && it != cameras.end()) chosen = &*it;
    }
    if (!chosen) refuse(cameras, choice, file, "no camera named \"" + choice + "\"");
  }
  if (!chosen->problem.empty()) {
    if (choice.empty()) throw InputError("glTF file " + file + ": " + chosen->problem);
    refuse(cameras, choice, file, chosen->problem);
  }
  return chosen;
}

}  // namespace penumbra
