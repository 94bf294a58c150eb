// What a glTF scene gets when its files lack it: a camera that frames the model, and
// the studio environment when nothing lights it, each said in one note. Decided once,
// at load (LoadOptions::defaults in io/scene_loader.h); nothing changes the scene after.
#pragma once
#include "core/scene.h"
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

// The share of the image's half-width and half-height the framed box may fill: the
// rest is margin, so no corner touches the border.
constexpr double kFrameFill = 1.0 / 1.1;

// `camera` (fov, image size and samples kept) moved to a three-quarter view of
// `bounds`: from +z turned 30 degrees towards +x and 20 degrees above, up = +y,
// looking at the box's centre, at the nearest distance that keeps every corner of the
// box within kFrameFill of the image's half-extents.
Camera frameBounds(const Camera& camera, const SceneBounds& bounds);

// A glTF scene after loading: `noCamera` when neither the model nor the JSON beside
// it places a camera. Records in scene.load what is missing and, when `add`, adds a
// camera framing the bounds and, without any light, the studio environment
// (core/lights/studio_environment.h), each with one note naming `model`. Throws
// InputError when the framed camera fails the camera checks (a model beyond float's reach).
void addSceneDefaults(const std::string& model, bool noCamera, bool add, Scene& scene);

}  // namespace penumbra
