// A model scene's defaults: the framing camera (its bounding sphere filling kFrameFill
// of the image's smaller dimension, in double) and the studio environment.
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

BoundingSphere sceneSphere(const Scene& scene) {
  return boundingSphere([&](const auto& f) {
    for (const TriangleMesh& m : scene.meshes) {
      for (const Vec3& p : m.positions) f(glm::dvec3(p), 0.0);
    }
    for (const Sphere& s : scene.spheres) f(glm::dvec3(s.center), double(s.radius));
  });
}

Camera frameSphere(const Camera& camera, const BoundingSphere& sphere) {
  const glm::dvec3 centre = sphere.empty() ? glm::dvec3(0.0) : sphere.centre;
  const double radius = std::max(sphere.radius, 0.0);
  // `back` points from the model to the eye; the frame is cameraFrame's, in double.
  const glm::dvec3 back(std::sin(kAzimuth) * std::cos(kElevation), std::sin(kElevation),
                        std::cos(kAzimuth) * std::cos(kElevation));
  // The smaller image dimension over the height: the share of fovY (or ortho_height) it spans.
  const double narrow = std::min(1.0, double(camera.width) / double(camera.height));
  Camera c = camera;
  double distance = 1.0;  // a model of no size is seen from one unit away
  if (camera.orthoHeight > 0.0f) {
    // The view's smaller extent is the sphere's diameter over kFrameFill; the eye stands outside it.
    if (radius > 0.0) c.orthoHeight = float(2.0 * radius / (kFrameFill * narrow));
    if (radius > 0.0) distance = 2.0 * radius;
  } else if (radius > 0.0) {
    // The sphere's silhouette is the cone of half-angle asin(radius / distance) about
    // the view axis: on the image plane a circle of radius tan of that, asked to be
    // kFrameFill of the smaller half-extent tanHalf.
    const double tanHalf = std::tan(0.5 * double(camera.fovY) * glm::pi<double>() / 180.0) * narrow;
    const double t = kFrameFill * tanHalf;
    distance = radius * std::sqrt(1.0 + 1.0 / (t * t));
  }
  c.position = Vec3(centre + back * distance);
  c.lookAt = Vec3(centre);
  c.up = Vec3(0.0f, 1.0f, 0.0f);
  return c;
}

void frameCamera(const std::string& file, bool asked, Scene& scene) {
  const std::string why = asked ? "--camera auto" : "no camera";
  const std::string keep =
      asked ? "--camera NAME|INDEX picks one of the file's" : "--no-defaults keeps the file as it is";
  const Camera c = frameSphere(scene.camera, sceneSphere(scene));
  const CameraProblem problem = cameraProblem(c);
  if (!problem.message.empty()) {
    const std::string instead = asked ? "one of the file's cameras" : "--no-defaults";
    throw InputError(file + ": " + why + ", and one framing its bounds fails: camera." + problem.key + ": " +
                     problem.message + " (give a camera in a JSON beside it, or use " + instead + ")");
  }
  scene.camera = c;
  scene.load.framedCamera = true;
  scene.load.notes.push_back(fmt::format("{}: {}; one frames the model from {} looking at {} (fov {:g}; {})", file,
                                         why, vec(c.position), vec(c.lookAt), c.fovY, keep));
}

ShadingModel defaultShadingModel(bool modelScene) { return modelScene ? kModelFileShadingModel : kDefaultShadingModel; }

void addSceneDefaults(const std::string& model, bool noCamera, bool add, Scene& scene, bool autoCamera) {
  LoadReport& report = scene.load;
  report.noCamera = noCamera;
  report.noLight = scene.lights.empty();
  if (autoCamera) frameCamera(model, true, scene);
  if (!add) return;
  if (report.noCamera && !autoCamera) frameCamera(model, false, scene);
  if (report.noLight) {
    addStudioEnvironment(scene, Color(1.0f), 1.0f, 0.0f);
    report.defaultSky = true;
    report.notes.push_back(model + ": no light; the studio environment lights it, a grey background behind "
                                   "(environment \"studio\"; --no-defaults keeps the file as it is)");
  }
}

}  // namespace penumbra
