// The pinhole camera's orthonormal frame, built once here so the loader checks
// exactly what the tracer will use (in float, as the tracer computes it).
#pragma once
#include "core/scene.h"

namespace penumbra {

struct CameraFrame {
  Vec3 forward, right, up;  // right = forward x camera.up, up = right x forward
};

inline CameraFrame cameraFrame(const Camera& c) {
  CameraFrame f;
  f.forward = glm::normalize(c.lookAt - c.position);
  f.right = glm::normalize(glm::cross(f.forward, c.up));
  f.up = glm::cross(f.right, f.forward);
  return f;
}

}  // namespace penumbra
