// Entry points of the scene loader: reads the file, parses it strictly
// (io/json_parse.h), applies --set overrides, then validates.
#include "io/scene_loader.h"

#include "core/error.h"
#include "io/float_checks.h"
#include "io/json_parse.h"
#include "io/json_reader.h"
#include "io/overrides.h"
#include "io/scene_sections.h"

#include <filesystem>
#include <fstream>
#include <sstream>

namespace penumbra {

namespace {

namespace fs = std::filesystem;
using nlohmann::json;

fs::path folderOf(const std::string& file) {
  std::error_code ec;
  fs::path dir = file.empty() ? fs::path(".") : fs::path(file).parent_path();
  if (dir.empty()) dir = ".";
  fs::path abs = fs::absolute(dir, ec);
  return ec ? dir : abs.lexically_normal();
}

Scene buildScene(const json& document, const LoadContext& context) {
  JsonNode root(document, "", context);
  if (!document.is_object()) {
    root.fail("a scene must be a JSON object, got " + describeJson(document));
  }
  root.allowKeys({"name", "camera", "lights", "materials", "objects", "render", "photons"});
  Scene scene;
  scene.file = context.file;
  if (root.has("name")) {
    scene.name = root.child("name").asString();
    if (scene.name.empty()) root.child("name").fail("must not be empty");
  } else {
    scene.name = context.file.empty() ? "scene" : fs::path(context.file).stem().string();
  }
  if (root.has("camera")) readCamera(root.child("camera"), scene.camera);
  if (root.has("lights")) readLights(root.child("lights"), scene.lights);
  // render first: the model decides how materials are checked.
  if (root.has("render")) readRender(root.child("render"), scene.render);
  readMaterials(root, scene);
  readObjects(root, scene);
  addEmitters(scene);
  checkSceneNumbers(root, scene);
  if (root.has("photons")) readPhotons(root.child("photons"), scene.photons);
  return scene;
}

}  // namespace

Scene parseScene(const std::string& jsonText, const std::string& fileName,
                 const std::vector<std::string>& overrides) {
  LoadContext context;
  context.file = fileName.empty() ? "<scene>" : fileName;
  context.baseDir = folderOf(fileName);
  json document = parseJsonDocument(jsonText, context.file);
  context.overridden = applyOverrides(document, overrides);
  try {
    Scene scene = buildScene(document, context);
    scene.file = fileName;
    return scene;
  } catch (const json::exception& e) {
    // Every access is type-checked first; this is a safety net, not a path.
    throwInputError(context.file + ": unexpected JSON error: " + parseProblem(e.what()));
  }
}

Scene loadScene(const std::string& path, const std::vector<std::string>& overrides) {
  std::error_code ec;
  if (!fs::is_regular_file(path, ec)) throwInputError(path + ": cannot open scene file");
  std::ifstream in(path, std::ios::binary);
  if (!in) throwInputError(path + ": cannot open scene file");
  std::ostringstream text;
  text << in.rdbuf();
  if (in.bad()) throwInputError(path + ": cannot read scene file");
  return parseScene(text.str(), path, overrides);
}

}  // namespace penumbra
