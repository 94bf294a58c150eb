// The thin lens's two numbers, worked out once here for the tracer, the checks and the
// docs: the aperture radius in scene units (from a radius or an f-number) and the
// focus distance. The lens sits at the camera position; the field of view stays fov's.
#pragma once
#include "core/scene.h"
#include <algorithm>
#include <cmath>

namespace penumbra {

// An f-number needs a focal length, which a field of view gives only with a sensor:
// Blender's default, 36 mm across the image's longer side, and a scene unit of 1 m
// (glTF's unit). So f = 18 mm / tan(half the longer side's field of view).
constexpr double kSensorWidthMm = 36.0;
constexpr double kSceneUnitMm = 1000.0;

// The focal length in mm of the full-frame lens that has this camera's field of view.
inline double focalLengthMm(const Camera& c) {
  const double tanY = std::tan(0.5 * double(c.fovY) * 3.14159265358979323846 / 180.0);
  const double longer = tanY * std::max(1.0, double(c.width) / double(c.height));
  return 0.5 * kSensorWidthMm / longer;
}

// The aperture's radius in scene units: the radius given, or f / (2 N) for an
// f-number N; 0 is the pinhole (and an orthographic camera has no lens).
inline float lensRadius(const Camera& c) {
  if (c.orthoHeight > 0.0f) return 0.0f;
  if (c.apertureRadius > 0.0f) return c.apertureRadius;
  if (c.fNumber > 0.0f) return static_cast<float>(focalLengthMm(c) / (2.0 * double(c.fNumber)) / kSceneUnitMm);
  return 0.0f;
}

// The distance from the lens to the plane in focus, along the view direction: the
// one given, else look_at's (so look_at is sharp).
inline float focusDistance(const Camera& c) {
  return c.focusDistance > 0.0f ? c.focusDistance : glm::length(c.lookAt - c.position);
}

}  // namespace penumbra
