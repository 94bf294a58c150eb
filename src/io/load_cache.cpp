// Scene loads that share files read them once (io/load_cache.h).
#include "io/load_cache.h"
#include "io/texture_check.h"

namespace penumbra {

const std::string& LoadCache::sceneText(const std::string& path, const std::function<std::string()>& read) {
  auto it = texts_.find(path);
  if (it == texts_.end()) it = texts_.emplace(path, read()).first;
  return it->second;
}

const LoadedModel& LoadCache::model(const std::string& path, const LoadLimits& limits) {
  auto it = models_.find(path);
  if (it == models_.end()) it = models_.emplace(path, loadModel(path, limits)).first;
  return it->second;
}

const std::string& LoadCache::textureProblem(const std::string& path) {
  auto it = textures_.find(path);
  if (it == textures_.end()) it = textures_.emplace(path, textureFileProblem(path)).first;
  return it->second;
}

LoadedModel loadModelFor(const LoadContext& context, const std::string& path) {
  return context.cache ? context.cache->model(path, context.limits) : loadModel(path, context.limits);
}

std::string textureProblemFor(const LoadContext& context, const std::string& path) {
  return context.cache ? context.cache->textureProblem(path) : textureFileProblem(path);
}

}  // namespace penumbra
