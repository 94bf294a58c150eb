// Output paths checked before any work: each must be writable, of a supported
// kind, distinct from the others, and never one of the render's own inputs.
#pragma once
#include "core/scene.h"
#include <string>
#include <vector>

namespace penumbra {

struct OutputPath {
  std::string path;
  std::string what;  // "-o", "--stats", ...: names the option in messages
  bool image = false;  // an image: .png or .exr, checked by image_io
};

// Every file the render reads: the scene's inputs (Scene::inputs: the scene or model
// file, its sidecar, buffers, images, meshes, MTLs, textures) and `scenePath` itself.
std::vector<std::string> sceneInputs(const Scene& scene, const std::string& scenePath);

// Throws InputError naming the option unless every output can be written
// (outputPathProblem: its directory, its name's and temp file's lengths), no two
// outputs name the same file and none names an input (compared canonically, and by
// inode where both exist).
void checkOutputs(const std::vector<OutputPath>& outputs, const std::vector<std::string>& inputs);

// One job of several (a batch): its name for messages, the files it writes and reads.
struct JobFiles {
  std::string name;
  std::vector<std::string> outputs, inputs;
};
// Throws InputError naming both jobs when a job writes a file another job writes or
// any job reads (checkOutputs has compared each job with itself).
void checkJobsApart(const std::vector<JobFiles>& jobs);

}  // namespace penumbra
