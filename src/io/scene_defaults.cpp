// A glTF scene's defaults: the framing camera (the nearest distance at which the
// bounding box's corners fit the image, in double) and the studio environment.
#include "io/scene_defaults.h"

#include "core/lights/studio_environment.h"
#include "core/error.h"
#include "io/camera_checks.h"

#include <fmt/format.h>
#include <algorithm>
#include <cmath>

namespace penumbra {

namespace {

// A three-quarter view: turned from +z towards +x, and a little above the model.
constexpr double kAzimuth = 30.0 * glm::pi<double>() / 180.0;
constexpr double kElevation = 20.0 * glm::pi<double>() / 180.0;

std::string vec(const Vec3& v) { return fmt::format("[{:.4g}, {:.4g}, {:.4g}]", v.x, v.y, v.z); }

}  // namespace

SceneBounds sceneBounds(const Scene& scene) {
  SceneBounds b;
  for (const TriangleMesh& m : scene.meshes) {
    for (const Vec3& p : m.positions) b.add(p);
  }
  for (const Sphere& s : scene.spheres) {
    b.add(s.center - Vec3(s.radius));
    b.add(s.center + Vec3(s.radius));
  }
  return b;
}

Camera frameBounds(const Camera& camera, const SceneBounds& bounds) {
  const glm::dvec3 lo(bounds.lo), hi(bounds.hi), centre = 0.5 * (lo + hi);
  // `back` points from the model to the eye; the frame is cameraFrame's, in double.
  const glm::dvec3 back(std::sin(kAzimuth) * std::cos(kElevation), std::sin(kElevation),
                        std::cos(kAzimuth) * std::cos(kElevation));
  const glm::dvec3 right = glm::normalize(glm::cross(-back, glm::dvec3(0.0, 1.0, 0.0)));
  const glm::dvec3 up = glm::cross(right, -back);
  const double tanY = std::tan(0.5 * double(camera.fovY) * glm::pi<double>() / 180.0) * kFrameFill;
  const double tanX = tanY * double(camera.width) / double(camera.height);
  // A corner at offset o lies at depth d - o.back from an eye at distance d; it is in
  // the image when |o.right| <= tanX depth and |o.up| <= tanY depth.
  const double reach = 0.5 * glm::length(hi - lo);
  double distance = 0.0, nearest = 0.0;
  for (int k = 0; k < 8; ++k) {
    const glm::dvec3 corner((k & 1) ? hi.x : lo.x, (k & 2) ? hi.y : lo.y, (k & 4) ? hi.z : lo.z);
    const glm::dvec3 o = corner - centre;
    const double along = glm::dot(o, back);
    distance = std::max(distance, along + std::max(std::fabs(glm::dot(o, right)) / tanX, std::fabs(glm::dot(o, up)) / tanY));
    nearest = std::max(nearest, along);
  }
  // The eye stays outside the box, and a box of no size is seen from one unit away.
  distance = std::max(distance, nearest + 1e-3 * reach);
  if (!(reach > 0.0)) distance = 1.0;
  Camera c = camera;
  c.position = Vec3(centre + back * distance);
  c.lookAt = Vec3(centre);
  c.up = Vec3(0.0f, 1.0f, 0.0f);
  return c;
}

void addSceneDefaults(const std::string& model, bool noCamera, bool add, Scene& scene) {
  LoadReport& report = scene.load;
  report.modelFile = model;
  report.noCamera = noCamera;
  report.noLight = scene.lights.empty();
  if (!add) return;
  if (report.noCamera) {
    const Camera c = frameBounds(scene.camera, sceneBounds(scene));
    const CameraProblem problem = cameraProblem(c);
    if (!problem.message.empty()) {
      throw InputError(model + ": has no camera, and one framing its bounds fails: camera." + problem.key + ": " +
                      problem.message + " (give a camera in a JSON beside it, or use --no-defaults)");
    }
    scene.camera = c;
    report.framedCamera = true;
    report.notes.push_back(fmt::format("{}: no camera; one frames the model from {} looking at {} (fov {:g}; "
                                       "--no-defaults keeps the file as it is)",
                                       model, vec(c.position), vec(c.lookAt), c.fovY));
  }
  if (report.noLight) {
    addStudioEnvironment(scene, Color(1.0f), 1.0f, 0.0f);
    report.defaultSky = true;
    report.notes.push_back(model + ": no light; the studio environment lights it, a grey background behind "
                                   "(environment \"studio\"; --no-defaults keeps the file as it is)");
  }
}

}  // namespace penumbra
