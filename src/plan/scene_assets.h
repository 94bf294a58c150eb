// A scene's Embree scene and textures: built once per geometry and shared by every
// render of it.
#pragma once
#include "geometry/trace_scene.h"
#include "trace/texture_lookup.h"
#include "core/scene.h"
#include <memory>

namespace penumbra {

// Built once per geometry; the tracer reads the Scene it was built from, which
// must outlive it (the render session keeps it with the assets).
struct SceneAssets {
  std::unique_ptr<TraceScene> tracer;
  std::unique_ptr<TextureLookup> textures;
  double bvhSeconds = 0.0;
  double bvhCpuSeconds = 0.0;  // the build's CPU seconds (a sweep charges each run a lone render's)
};
// The BVH alone: photons, pilots and plans trace it; textures wait for a frame that
// reads them (loadTextures), so a run that shades nothing never loads the image module.
SceneAssets prepareAssets(const Scene& scene);
// The scene's textures (procedural ones generated once into the cache); null: none.
std::unique_ptr<TextureLookup> loadTextures(const Scene& scene);

}  // namespace penumbra
