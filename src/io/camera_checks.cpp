// One definition of a renderable camera, shared by the scene reader, the glTF loader
// and batch orbits, so no path into the tracer skips a check.
#include "io/camera_checks.h"

#include "core/camera_frame.h"
#include "core/error.h"
#include "core/thin_lens.h"
#include "io/float_checks.h"

#include <algorithm>
#include <cmath>
#include <cstdio>

namespace penumbra {

namespace {

// A normalised float vector that came out as one: not NaN, not a denormal mess.
bool isUnit(const Vec3& v) {
  return isFinite(v) && std::fabs(glm::length(v) - 1.0f) < 1e-3f;
}

bool withinLimit(const Vec3& p) {
  return isFinite(p) && std::max({std::fabs(p.x), std::fabs(p.y), std::fabs(p.z)}) <= kMaxCoordinate;
}

std::string shown(double v) {
  char buf[32];
  std::snprintf(buf, sizeof buf, "%g", v);
  return buf;
}

std::string positionProblem(const Vec3& p) {
  if (!isFinite(p)) return "every coordinate must be finite";
  return "every coordinate must be within +-1e+15 (Embree's ray range with float precision to spare), got " +
         shown(std::max({std::fabs(p.x), std::fabs(p.y), std::fabs(p.z)}));
}

// The thin lens (core/thin_lens.h): a radius or an f-number, not both; a focus plane
// in front of the lens; a perspective camera (parallel rays have no focus).
CameraProblem lensProblem(const Camera& c) {
  if (!(c.apertureRadius >= 0.0f && c.apertureRadius <= static_cast<float>(kMaxCoordinate))) {
    return {"aperture_radius", "must be 0 (a pinhole) or a radius up to 1e15 scene units, got " + shown(c.apertureRadius)};
  }
  if (!(c.fNumber >= 0.0f && c.fNumber <= 1e15f)) {
    return {"f_number", "must be above 0 and at most 1e15, got " + shown(c.fNumber)};
  }
  if (c.apertureRadius > 0.0f && c.fNumber > 0.0f) {
    return {"f_number", "give aperture_radius or f_number, not both (both size the aperture)"};
  }
  if (!(c.focusDistance >= 0.0f && c.focusDistance <= static_cast<float>(kMaxCoordinate))) {
    return {"focus_distance", "must be above 0 and at most 1e15 scene units, got " + shown(c.focusDistance)};
  }
  const bool lens = c.apertureRadius > 0.0f || c.fNumber > 0.0f;
  if (lens && c.orthoHeight > 0.0f) {
    return {c.apertureRadius > 0.0f ? "aperture_radius" : "f_number",
            "an orthographic camera (ortho_height > 0) has no lens: its rays are parallel"};
  }
  if (lens && !(focusDistance(c) > 0.0f)) {
    return {"focus_distance", "the lens needs a focus distance above 0 (look_at is too close to position)"};
  }
  return {};
}

}  // namespace

CameraProblem cameraProblem(const Camera& c) {
  if (!withinLimit(c.position)) return {"position", positionProblem(c.position)};
  if (!withinLimit(c.lookAt)) return {"look_at", positionProblem(c.lookAt)};
  if (!(c.fovY > 0.0f && c.fovY < 180.0f)) {
    return {"fov", "the vertical field of view must be between 0 and 180 degrees (both excluded), got " + shown(c.fovY)};
  }
  if (!(c.orthoHeight >= 0.0f && c.orthoHeight <= 1e15f)) {
    return {"ortho_height", "must be 0 (a pinhole) or a height up to 1e15 scene units, got " + shown(c.orthoHeight)};
  }
  if (c.width < 1 || c.width > 16384) return {"width", "must be 1..16384 pixels, got " + std::to_string(c.width)};
  if (c.height < 1 || c.height > 16384) return {"height", "must be 1..16384 pixels, got " + std::to_string(c.height)};
  if (c.spp < 1 || c.spp > 4096) return {"spp", "must be 1..4096, got " + std::to_string(c.spp)};
  // The film's rays start at position + offsets, in float as CameraRays makes them.
  const float step = c.orthoHeight / static_cast<float>(c.height);
  const float reach = std::max({std::fabs(c.position.x), std::fabs(c.position.y), std::fabs(c.position.z)});
  if (c.orthoHeight > 0.0f && !(step >= static_cast<float>(kMinPixelStepRatio) * reach)) {
    return {"ortho_height", "a pixel (ortho_height / height = " + shown(c.orthoHeight) + " / " + std::to_string(c.height) +
                                " = " + shown(step) + ") must be >= 2^-21 x the camera position's largest coordinate (" +
                                shown(reach) + ") = " + shown(kMinPixelStepRatio * reach) +
                                ": finer, single precision puts neighbouring pixels' rays on one point"};
  }
  // The frame the tracer will build, in float: a length of 1e-30 is fine in double
  // but its square underflows in float: NaN.
  const CameraFrame frame = cameraFrame(c);
  if (!isUnit(frame.forward)) {
    return {"look_at", "look_at equals position, or is too close to it for a view direction in single precision"};
  }
  if (!isUnit(glm::normalize(c.up))) {
    return {"up", "up has no direction in single precision (zero, or too short or long to normalise)"};
  }
  const float sine = glm::length(glm::cross(frame.forward, glm::normalize(c.up)));
  if (!(sine > 1e-6f) || !isUnit(frame.right)) return {"up", "up is parallel to the view direction (look_at - position)"};
  return lensProblem(c);
}

void checkCamera(const Camera& camera, const std::string& where) {
  const CameraProblem p = cameraProblem(camera);
  if (!p.message.empty()) throw InputError(where + ": " + p.key + ": " + p.message);
}

}  // namespace penumbra
