// Entry points of the scene loader: reads the file, parses it strictly
// (io/json_parse.h), applies --set overrides, then validates. A glTF or OBJ file is a
// scene too: its meshes, camera and lights, with an optional JSON of the same stem.
#include "io/scene_loader.h"
#include "io/input_file.h"

#include "core/error.h"
#include "io/float_checks.h"
#include "io/json_parse.h"
#include "io/json_reader.h"
#include "io/mesh_tangents.h"
#include "io/load_cache.h"
#include "io/media_binding.h"
#include "io/media_reader.h"
#include "io/model_import.h"
#include "io/overrides.h"
#include "io/scene_defaults.h"
#include "io/scene_sections.h"
#include "io/scene_warnings.h"
#include "io/transform.h"

#include <fmt/format.h>
#include <algorithm>
#include <cmath>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <iostream>
#include <sstream>
#ifdef __GLIBC__
#include <malloc.h>
#endif

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

// The model scene's meshes (own materials; faces without one take "default"), and its
// punctual lights after the JSON's.
void addSceneModel(const JsonNode& root, LoadedModel& model, Scene& scene) {
  int fallback = -1;
  for (size_t i = 0; i < scene.materials.size() && fallback < 0; ++i) {
    if (scene.materials[i].name == "default") fallback = static_cast<int>(i);
  }
  if (fallback < 0) {
    Material m;
    m.name = "default";
    fallback = static_cast<int>(scene.materials.size());
    scene.materials.push_back(m);
    ++scene.load.implicitMaterials;
  }
  addModelMeshes(root, model, -1, fallback, Transform{}, scene);
  for (const Light& light : model.lights) {
    checkPositions(root, {light.position}, "the model's light positions");
    scene.lights.push_back(light);
  }
}

// Whether the settings (the sidecar, the overrides) choose a quality: camera.spp or
// photons.passes; without one a model scene renders to a default bound.
bool givesQuality(const JsonNode& root) {
  auto sets = [&](const char* section, const char* key) { return root.has(section) && root.child(section).has(key); };
  return sets("camera", "spp") || sets("photons", "passes");
}

Scene buildScene(const json& document, const LoadContext& context, const std::string& modelPath,
                 const LoadOptions& options) {
  JsonNode root(document, "", context);
  if (!document.is_object()) {
    root.fail("a scene must be a JSON object, got " + describeJson(document));
  }
  root.allowKeys({"name", "camera", "lights", "materials", "objects", "render", "photons", "environment", "media"});
  LoadedModel model;
  if (!modelPath.empty()) {
    try {
      model = loadModelFor(context, modelPath);
    } catch (const ModelError& e) {
      throwInputError(e.what());
    }
  }
  Scene scene;
  const std::string& source = modelPath.empty() ? context.file : modelPath;
  const GltfCamera* camera = chooseGltfCamera(model.cameras, options.camera, source);  // --camera
  if (camera) scene.camera = camera->camera;
  scene.file = context.file;
  // The settings file first (the sidecar of a glTF scene), then the model's files.
  if (!context.file.empty() && context.file != "<scene>" && context.file != "<stdin>") scene.inputs.push_back(context.file);
  scene.inputs.insert(scene.inputs.end(), model.files.begin(), model.files.end());
  if (root.has("name")) {
    scene.name = root.child("name").asString();
    if (scene.name.empty()) root.child("name").fail("must not be empty");
  } else {
    scene.name = context.file.empty() ? "scene" : fs::path(context.file).stem().string();
  }
  static const json kNoCamera = json::object();
  if (root.has("camera")) {
    // Overrides the model's camera key by key.
    readCamera(root.child("camera"), scene.camera, camera ? camera->aspect : 0.0);
  } else if (!modelPath.empty()) {
    readCamera(JsonNode(kNoCamera, "camera", context), scene.camera);  // checks the model's camera
  }
  if (root.has("lights")) readLights(root.child("lights"), scene.lights);
  // render first: the model decides how materials are checked.
  scene.render.model = defaultShadingModel(!modelPath.empty());
  if (root.has("render")) readRender(root.child("render"), scene.render);
  // Media before objects, which name them; after render, whose model may refuse them.
  readMedia(root, scene);
  readSceneMedium(root, scene);
  if (!root.has("materials")) ++scene.load.implicitMaterials;  // readMaterials adds "default"
  readMaterials(root, scene);
  readObjects(root, scene);
  if (!modelPath.empty()) addSceneModel(root, model, scene);
  addMissingTangents(scene);  // normal-mapped meshes only
  for (TriangleMesh& mesh : scene.meshes) padVertices(mesh.positions);  // the BVH reads them in place
  for (TriangleMesh& mesh : scene.boundaryMeshes) padVertices(mesh.positions);
  if (scene.lights.size() > 65535) root.fail("at most 65535 lights, the model's included");
  addEmitters(scene);
  addMeshEmitters(scene);
  if (root.has("environment")) readEnvironment(root.child("environment"), scene);
  if (!modelPath.empty()) {
    scene.load.modelFile = modelPath;
    scene.load.qualityGiven = givesQuality(root);
    // A camera the user placed (the model's, or position / look_at beside it) is kept.
    const bool placed = camera || (root.has("camera") && (root.child("camera").has("position") ||
                                                          root.child("camera").has("look_at")));
    addSceneDefaults(modelPath, !placed, options.defaults, scene, options.camera == "auto");
  } else if (options.camera == "auto") {
    frameCamera(context.file, true, scene);  // a JSON scene framed on what it holds
  }
  checkSceneNumbers(root, scene);
  if (root.has("photons")) readPhotons(root.child("photons"), scene.photons);
  bindMedia(scene);  // last: the camera, lights and objects are where they will render
  // Each file once, in the order first read (a glTF without sidecar is both).
  std::vector<std::string> inputs;
  for (std::string& f : scene.inputs) {
    if (std::find(inputs.begin(), inputs.end(), f) == inputs.end()) inputs.push_back(std::move(f));
  }
  scene.inputs = std::move(inputs);
  return scene;
}

// The largest scene document: a scene's JSON names its meshes and textures in
// files of their own, so even a big one is a few megabytes of text.
constexpr size_t kMaxSceneBytes = 64u << 20;

// A scene's text, read in chunks so binary data (a NUL byte) or an endless stream
// is refused as soon as it shows, not after the whole of it is in memory.
std::string readSceneText(std::istream& in, const std::string& name) {
  std::string text;
  char chunk[1 << 16];
  while (in.read(chunk, sizeof chunk) || in.gcount() > 0) {
    const size_t n = static_cast<size_t>(in.gcount());
    if (const void* nul = std::memchr(chunk, '\0', n)) {
      throwInputError(fmt::format("{}: binary data, not a JSON scene (a NUL byte at offset {})", name,
                                  text.size() + (static_cast<const char*>(nul) - chunk)));
    }
    if (text.size() + n > kMaxSceneBytes) {
      throwInputError(fmt::format("{}: more than {} MB of JSON, not a scene (meshes and textures belong in "
                                  "files of their own)", name, kMaxSceneBytes >> 20));
    }
    text.append(chunk, n);
  }
  if (in.bad()) throwInputError(name + ": cannot read scene file");
  return text;
}

std::string readText(const std::string& path) {
  if (const std::string why = unreadableFileReason(path); !why.empty()) throwInputError(path + ": cannot open scene file: " + why);
  std::ifstream in(path, std::ios::binary);
  if (!in) throwInputError(path + ": cannot open scene file");
  return readSceneText(in, path);
}

// What loading freed (a model's file bytes and parsed buffers, the readers' own
// arrays) goes back to the system rather than staying in glibc's heap, where it would
// stay resident beneath the BVH built next.
void returnFreedHeap() {
#ifdef __GLIBC__
  malloc_trim(0);
#endif
}

// `modelPath` non-empty: a model scene, `jsonText` its settings ("" = none).
Scene parseSceneWith(const std::string& jsonText, const std::string& fileName,
                     const std::vector<std::string>& overrides, const std::string& modelPath,
                     const LoadLimits& limits, const LoadOptions& options = {}) {
  LoadContext context;
  context.limits = limits;
  context.cache = options.cache;
  context.file = fileName.empty() ? "<scene>" : fileName;
  context.baseDir = folderOf(fileName);
  json document = jsonText.empty() && !modelPath.empty() ? json::object()
                                                          : parseJsonDocument(jsonText, context.file);
  context.overridden = applyOverrides(document, overrides);
  try {
    Scene scene = buildScene(document, context, modelPath, options);
    scene.file = modelPath.empty() ? fileName : modelPath;
    if (std::string warning = noLightWarning(scene); !warning.empty()) scene.load.notes.push_back(std::move(warning));
    returnFreedHeap();
    return scene;
  } catch (const json::exception& e) {
    // Every access is type-checked first; this is a safety net, not a path.
    throwInputError(context.file + ": unexpected JSON error: " + parseProblem(e.what()));
  }
}

}  // namespace

std::vector<std::string> LoadOptions::flags() const {
  std::vector<std::string> out;
  if (!defaults) out.push_back("--no-defaults");
  if (!camera.empty()) out.push_back("--camera " + camera);
  return out;
}

Scene parseScene(const std::string& jsonText, const std::string& fileName,
                 const std::vector<std::string>& overrides, const LoadLimits& limits) {
  return parseSceneWith(jsonText, fileName, overrides, "", limits);
}

Scene loadScene(const std::string& path, const std::vector<std::string>& overrides, const LoadLimits& limits,
                const LoadOptions& options) {
  // "-": the JSON comes from stdin; relative paths in it resolve against the working folder.
  if (path == "-") {
    LoadOptions once = options;  // --camera applies; nothing read for it is kept for later loads
    once.cache = nullptr;
    return parseSceneWith(readSceneText(std::cin, "<stdin>"), "<stdin>", overrides, "", limits, once);
  }
  // Read through the cache, where there is one: the text is read once per process.
  auto text = [&](const std::string& file) {
    return options.cache ? options.cache->sceneText(file, [&] { return readText(file); }) : readText(file);
  };
  if (!isModelPath(path)) return parseSceneWith(text(path), path, overrides, "", limits, options);
  if (const std::string why = unreadableFileReason(path); !why.empty()) throwInputError(path + ": cannot open scene file: " + why);
  std::error_code ec;
  // model.glb renders with model.json's settings when there is one.
  const std::string sidecar = fs::path(path).replace_extension(".json").string();
  const bool hasSidecar = fs::is_regular_file(sidecar, ec);
  return parseSceneWith(hasSidecar ? text(sidecar) : "", hasSidecar ? sidecar : path, overrides, path, limits,
                        options);
}

}  // namespace penumbra
