// A scene's BVH and textures (plan/scene_assets.h).
#include "plan/scene_assets.h"
#include "core/cpu_time.h"
#include "io/texture_gen.h"
#include <optional>
#include <string>
#include <vector>

namespace penumbra {

std::unique_ptr<TextureLookup> loadTextures(const Scene& scene) {
  if (scene.textures.empty()) return nullptr;
  std::vector<std::string> paths;
  std::vector<bool> data;
  std::vector<std::optional<TextureSampling>> samplers;
  for (const Texture& t : scene.textures) {
    // Procedural textures are generated once into the cache, then read like files.
    paths.push_back(t.path.rfind("builtin:", 0) == 0 ? builtinTexturePath(t.path) : t.path);
    data.push_back(t.data);
    samplers.push_back(t.sampler);
  }
  return std::make_unique<TextureLookup>(paths, data, samplers);
}

SceneAssets prepareAssets(const Scene& scene) {
  SceneAssets assets;
  const CpuSpan clock;
  assets.tracer = std::make_unique<TraceScene>(scene);
  assets.bvhSeconds = clock.wallSeconds();
  assets.bvhCpuSeconds = clock.cpuSeconds();
  return assets;
}

}  // namespace penumbra
