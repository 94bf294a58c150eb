// The files several scene loads of one process share, read once: scene texts,
// model files and texture checks. A batch's jobs that name one scene (an orbit's
// frames, one scene under several overrides) read and decode its files once.
#pragma once
#include "io/json_reader.h"
#include "io/load_limits.h"
#include "io/model_import.h"
#include <cstddef>
#include <functional>
#include <map>
#include <string>

namespace penumbra {

class LoadCache {
 public:
  // The text of a scene file, read by `read` the first time.
  const std::string& sceneText(const std::string& path, const std::function<std::string()>& read);
  // A model file (io/model_import.h), loaded the first time; a failure is not kept.
  const LoadedModel& model(const std::string& path, const LoadLimits& limits);
  // textureFileProblem's answer for a file, decoded the first time.
  const std::string& textureProblem(const std::string& path);

  // Scene files read from disk (each once), model files loaded, textures decoded.
  size_t sceneReads() const { return texts_.size(); }
  size_t modelReads() const { return models_.size(); }
  size_t textureChecks() const { return textures_.size(); }

 private:
  std::map<std::string, std::string> texts_;
  std::map<std::string, LoadedModel> models_;
  std::map<std::string, std::string> textures_;
};

// Through the context's cache when it has one, else read now.
LoadedModel loadModelFor(const LoadContext& context, const std::string& path);
std::string textureProblemFor(const LoadContext& context, const std::string& path);

}  // namespace penumbra
