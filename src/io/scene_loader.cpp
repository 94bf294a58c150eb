// Entry points of the scene loader: reads the file, turns JSON syntax errors
// into FILE:LINE:COLUMN messages, applies --set overrides, then validates.
#include "io/scene_loader.h"

#include "core/error.h"
#include "io/float_checks.h"
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

// 1-based line and column of the 0-based byte offset in text.
std::string lineColumn(const std::string& text, size_t offset) {
  offset = std::min(offset, text.size());
  size_t line = 1, lineStart = 0;
  for (size_t i = 0; i < offset; ++i) {
    if (text[i] == '\n') {
      ++line;
      lineStart = i + 1;
    }
  }
  return std::to_string(line) + ":" + std::to_string(offset - lineStart + 1);
}

// nlohmann's what() is "[json.exception.parse_error.101] parse error at line 3,
// column 4: syntax error while ..."; keep only the part after the position.
std::string parseProblem(const std::string& what) {
  size_t at = what.find("column ");
  size_t colon = what.find(": ", at == std::string::npos ? 0 : at);
  if (colon != std::string::npos) return what.substr(colon + 2);
  size_t bracket = what.find("] ");
  return bracket == std::string::npos ? what : what.substr(bracket + 2);
}

json parseJson(const std::string& text, const std::string& file) {
  try {
    return json::parse(text);
  } catch (const json::parse_error& e) {
    // e.byte is 1-based: the offending character sits at offset byte - 1.
    size_t offset = e.byte > 0 ? e.byte - 1 : 0;
    throwInputError(file + ":" + lineColumn(text, offset) +
                    ": JSON syntax error: " + parseProblem(e.what()));
  } catch (const json::out_of_range& e) {
    // Raised for numbers beyond double range ("1e400"); nlohmann gives no
    // position, so locate the literal it quotes.
    std::string problem = parseProblem(e.what());
    size_t q1 = problem.find('\''), q2 = problem.rfind('\'');
    if (q1 != std::string::npos && q2 > q1) {
      size_t offset = text.find(problem.substr(q1 + 1, q2 - q1 - 1));
      if (offset != std::string::npos) {
        throwInputError(file + ":" + lineColumn(text, offset) + ": JSON number error: " +
                        problem + " (numbers must be finite)");
      }
    }
    throwInputError(file + ": JSON number error: " + problem);
  } catch (const json::exception& e) {
    throwInputError(file + ": JSON error: " + parseProblem(e.what()));
  }
}

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
  json document = parseJson(jsonText, context.file);
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
