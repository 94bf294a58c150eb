// The checks every camera meets before it reaches the tracer, whichever file (scene
// JSON, glTF) or plan (a batch orbit) made it: bounded position, a field of view,
// an image size, a thin lens that can focus, and a view frame that exists in single
// precision.
#pragma once
#include "core/scene.h"
#include <string>

namespace penumbra {

// What is wrong with a camera: `key` is the scene-format key at fault ("position",
// "look_at", "up", "fov", "width", "height", "spp", "aperture_radius", ...); an empty
// message = nothing.
struct CameraProblem {
  std::string key;
  std::string message;
};

// The first problem of `camera`, checked in float as core/camera_frame.h builds it.
CameraProblem cameraProblem(const Camera& camera);

// Throws InputError("<where>: <key>: <problem>") when `camera` has a problem;
// `where` names the camera for the reader ("scene.json: camera", "batch job 3").
void checkCamera(const Camera& camera, const std::string& where);

}  // namespace penumbra
