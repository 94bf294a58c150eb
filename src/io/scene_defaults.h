// What a model scene gets when its files lack it: a camera that frames the model, and
// the studio environment when nothing lights it, each said in one note. Decided once,
// at load (LoadOptions::defaults in io/scene_loader.h); nothing changes the scene after.
#pragma once
#include "core/scene.h"
#include "io/bounding_sphere.h"
#include <string>

namespace penumbra {

// An axis-aligned box; empty (lo > hi) until a point is added.
struct SceneBounds {
  Vec3 lo{3.0e38f}, hi{-3.0e38f};
  bool empty() const { return lo.x > hi.x; }
  void add(const Vec3& p) { lo = glm::min(lo, p); hi = glm::max(hi, p); }
};

// Every mesh vertex and sphere of `scene`.
SceneBounds sceneBounds(const Scene& scene);

// The share of the image's smaller dimension (width or height) the silhouette of the
// framed model's bounding sphere spans; the rest is margin.
constexpr double kFrameFill = 0.9;

// The ball enclosing every mesh vertex and sphere of `scene` (io/bounding_sphere.h).
BoundingSphere sceneSphere(const Scene& scene);

// `camera` (fov, image size and samples kept) moved to a three-quarter view of
// `sphere`: from +z turned 30 degrees towards +x and 20 degrees above, up = +y,
// looking at its centre, at the distance where its silhouette spans kFrameFill of
// the image's smaller dimension (an orthographic camera: its ortho height set so).
Camera frameSphere(const Camera& camera, const BoundingSphere& sphere);

// Frames `scene`'s camera on everything in it, with one note naming `file`: `asked`
// by --camera auto, else the model has no camera. Throws InputError when the framed
// camera fails the camera checks (a model beyond float's reach).
void frameCamera(const std::string& file, bool asked, Scene& scene);

// The shading model a scene renders in where render.model is not set, decided before
// its materials are read: kModelFileShadingModel for a glTF or OBJ file given as the
// scene (`modelScene`), kDefaultShadingModel for a JSON scene, models it imports too.
ShadingModel defaultShadingModel(bool modelScene);

// A glTF scene after loading: `noCamera` when neither the model nor the JSON beside
// it places a camera. Records in scene.load what is missing and, when `add`, adds a
// camera framing the model (always with `autoCamera`: --camera auto) and, without any
// light, the studio environment (core/lights/studio_environment.h), each with one note
// naming `model`. Throws InputError when the framed camera fails the camera checks (a
// model beyond float's reach).
void addSceneDefaults(const std::string& model, bool noCamera, bool add, Scene& scene, bool autoCamera = false);

}  // namespace penumbra
