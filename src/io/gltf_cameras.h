// A glTF file's cameras as its nodes place them, and the one --camera picks
// (LoadOptions::camera): by default the first its node tree meets.
#pragma once
#include "core/scene.h"
#include <glm/mat4x4.hpp>
#include <string>
#include <vector>

namespace tinygltf {
class Model;
}

namespace penumbra {

// One entry of the file's "cameras", by index.
struct GltfCamera {
  std::string name;      // cameras[i].name, "" = none
  std::string nodeName;  // the name of the first node placing it
  int order = -1;        // its place among the cameras the node tree meets; -1: no node of the scene places it
  bool used = false;     // perspective or orthographic: other types are skipped (a warning says so)
  Camera camera;         // as that node places it
  double aspect = 0.0;   // width / height, 0 = none
  std::string problem;   // why it cannot be used as placed (from "cameras[i]" on), "" = it can
};

// The file's cameras, one per entry of `m.cameras`, none placed yet.
std::vector<GltfCamera> gltfCameras(const tinygltf::Model& m);

// Camera `index`, placed by node `node` (transform `world`): the first node to name
// a camera places it; later ones are ignored. A camera that fails the JSON camera's
// checks as placed keeps the reason in `problem`, said only when it is chosen.
void placeGltfCamera(const tinygltf::Model& m, int index, int node, const glm::dmat4& world, const std::string& path,
                     std::vector<GltfCamera>& cameras);

// The camera `choice` (--camera) picks from the `cameras` of model `file`: "" the
// first the node tree meets (null when none), "auto" none (null: the model is
// framed), digits an index into the file's "cameras" (0-based), else a camera's name
// or, failing that, its node's name. Throws InputError, one line naming the file and
// the cameras it has, for a name or index it lacks or a camera that cannot be used.
const GltfCamera* chooseGltfCamera(const std::vector<GltfCamera>& cameras, const std::string& choice,
                                   const std::string& file);

}  // namespace penumbra
