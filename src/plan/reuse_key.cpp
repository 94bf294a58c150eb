// Reuse keys: the scene document minus what cannot change the shared piece.
// Conservative by construction: a key not named here stays in, so an unknown or
// new setting can only prevent sharing, never share wrongly.
#include "plan/reuse_key.h"
#include "core/shading_model.h"
#include "core/error.h"
#include "io/json_parse.h"
#include "io/model_import.h"
#include "io/overrides.h"
#include <fmt/format.h>
#include <filesystem>
#include <fstream>
#include <sstream>

namespace penumbra {

namespace fs = std::filesystem;

const std::vector<std::string>& gatherOnlyPhotonKeys() {
  // The budgets go too: a smaller one is cut out of the larger emission.
  static const std::vector<std::string> keys = {
      "shadow", "indirect", "global", "caustic", "volume",              // budgets (prefix reuse)
      "k_shadow", "k_indirect", "k_global", "k_caustic", "k_volume",    // gathers
      "max_radius", "radius", "volume_radius", "alpha", "gate", "lookup", "lookup_cell"};
  return keys;
}

std::string inputsStamp(const std::vector<std::string>& inputs) {
  std::string stamp;
  for (const std::string& path : inputs) {
    std::error_code sizeError, timeError;
    const auto size = fs::file_size(path, sizeError);
    const auto time = fs::last_write_time(path, timeError);
    stamp += path;
    stamp += sizeError || timeError ? " ?\n" : fmt::format(" {} {}\n", size, time.time_since_epoch().count());
  }
  return stamp;
}

ReuseKeys reuseKeys(const std::string& scenePath, const std::vector<std::string>& overrides) {
  // A model scene's document is its settings file beside it (model.json), if any;
  // the model itself is geometry, named by its path in both keys.
  std::string documentPath = scenePath;
  if (isModelPath(scenePath)) documentPath = fs::path(scenePath).replace_extension(".json").string();
  std::string text = "{}";
  if (documentPath == scenePath || fs::is_regular_file(documentPath)) {
    std::ifstream in(documentPath, std::ios::binary);
    if (!in) throw InputError(documentPath + ": cannot open scene file");
    std::stringstream buffer;
    buffer << in.rdbuf();
    text = buffer.str();
  }
  nlohmann::json doc = parseJsonDocument(text, documentPath);
  applyOverrides(doc, overrides);
  if (!doc.is_object()) throw InputError(scenePath + ": a scene must be a JSON object");

  ReuseKeys keys;
  nlohmann::json geometry = doc;
  geometry.erase("camera");
  geometry.erase("photons");
  geometry.erase("name");
  nlohmann::json model = doc.contains("render") && doc["render"].is_object() && doc["render"].contains("model")
                             ? doc["render"]["model"]
                             : nlohmann::json(shadingModelName(kDefaultShadingModel));
  geometry["render"] = {{"model", model}};
  // The medium filling the scene is part of the loaded scene that renders share.
  if (doc.contains("render") && doc["render"].is_object() && doc["render"].contains("medium")) {
    geometry["render"]["medium"] = doc["render"]["medium"];
  }
  keys.geometry = scenePath + "\n" + geometry.dump();

  nlohmann::json photons = doc;
  photons.erase("camera");
  photons.erase("name");
  if (photons.contains("render") && photons["render"].is_object()) {
    photons["render"].erase("max_depth");  // camera-side recursion; photons use max_bounces
    photons["render"].erase("aov");        // the view decides which maps are read, not emitted
    // Camera and single-scattering samples: how many each pixel takes changes no photon.
    for (const char* k : {"adaptive", "adaptive_threshold", "adaptive_max_spp", "volume_samples"}) photons["render"].erase(k);
  }
  if (photons.contains("photons") && photons["photons"].is_object()) {
    for (const std::string& k : gatherOnlyPhotonKeys()) photons["photons"].erase(k);
  }
  keys.photons = scenePath + "\n" + photons.dump();
  return keys;
}

}  // namespace penumbra
