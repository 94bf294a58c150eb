// The "media" section and the names that refer to it: each medium checked key by key
// (coefficients >= 0 and finite, g in (-1, 1)) before any density file is read.
#include "io/media_reader.h"

#include "core/media/density_grid.h"
#include "io/closed_mesh.h"
#include "io/suggest.h"
#include "io/vdb_reader.h"

#include <fmt/format.h>
#include <unordered_set>

namespace penumbra {

namespace {

// Henyey–Greenstein's phase diverges at |g| = 1 (a delta): open at both ends.
const Range kAsymmetry{-1.0, 1.0, true, true};

// A coefficient per scene unit: one number or [r, g, b], each in [0, 1e30]. 1e30 is
// opaque for any scene; the cap keeps sigma_a + sigma_s, times a density, finite.
constexpr double kMaxCoefficient = 1e30;
const Range kCoefficient = Range::between(0.0, kMaxCoefficient);

Color readCoefficient(const JsonNode& node) {
  if (node.value().is_number()) return Color(node.asFloat(kCoefficient));
  if (!node.value().is_array() || node.value().size() != 3) {
    node.fail("must be a number or [r, g, b] (per scene unit), got " + describeJson(node.value()));
  }
  return Color(node.element(0).asFloat(kCoefficient), node.element(1).asFloat(kCoefficient),
               node.element(2).asFloat(kCoefficient));
}

Medium readMedium(const JsonNode& node, Scene& scene) {
  node.allowKeys({"name", "sigma_a", "sigma_s", "g", "emission", "density"});
  Medium m;
  const JsonNode name = node.required("name", " for a medium");
  m.name = name.asString();
  if (m.name.empty()) name.fail("must not be empty");
  if (node.has("sigma_a")) m.sigmaA = readCoefficient(node.child("sigma_a"));
  if (node.has("sigma_s")) m.sigmaS = readCoefficient(node.child("sigma_s"));
  m.g = node.floatOr("g", m.g, kAsymmetry);
  m.emission = node.colorOr("emission", m.emission);
  if (node.has("density")) {
    m.density = readDensity(node.child("density"), scene);
    const double densest = double(maxComponent(m.sigmaT())) * m.density->maxDensity;
    if (densest > kMaxCoefficient) {
      node.child("density").fail(fmt::format("makes sigma_t up to {:g} per scene unit; at most {:g} (an opaque "
                                             "medium needs no more)", densest, kMaxCoefficient));
    }
  }
  return m;
}

}  // namespace

void readMedia(const JsonNode& root, Scene& scene) {
  if (!root.has("media")) return;
  const JsonNode media = root.child("media");
  const size_t count = media.arraySize();
  if (count > 0 && scene.render.model == ShadingModel::Classic) {
    const nlohmann::json& first = media.element(0).value();
    const std::string name = first.is_object() && first.contains("name") && first["name"].is_string()
                                 ? " (\"" + first["name"].get<std::string>() + "\")" : "";
    media.element(0).fail("media need the physical model (render.model \"physical\"); this medium" + name +
                          " is in a classic scene");
  }
  // Indices are 32-bit in the interfaces, but a scene with thousands of media is a typo.
  if (count > 4096) media.fail("at most 4096 media");
  std::unordered_set<std::string> names;
  for (size_t i = 0; i < count; ++i) {
    const JsonNode node = media.element(i);
    // Names first: a duplicate is refused before its density file is read.
    node.requireObject();
    if (node.has("name") && node.child("name").value().is_string() &&
        !names.insert(node.child("name").value().get<std::string>()).second) {
      node.child("name").fail("duplicate medium name " + describeJson(node.child("name").value()));
    }
  }
  for (size_t i = 0; i < count; ++i) scene.media.push_back(readMedium(media.element(i), scene));
}

int resolveMedium(const JsonNode& node, const Scene& scene) {
  const std::string name = node.asString();
  std::vector<std::string> names;
  for (size_t i = 0; i < scene.media.size(); ++i) {
    if (scene.media[i].name == name) return static_cast<int>(i);
    names.push_back(scene.media[i].name);
  }
  if (names.empty()) node.fail("unknown medium " + describeJson(node.value()) + ": the scene has no \"media\"");
  node.fail("unknown medium " + describeJson(node.value()) + didYouMean(name, names));
}

int objectMedium(const JsonNode& object, const Scene& scene) {
  return object.has("medium") ? resolveMedium(object.child("medium"), scene) : kNoMedium;
}

void placeMediumMeshes(const JsonNode& object, int medium, Scene& scene, size_t first) {
  if (medium == kNoMedium) return;
  std::vector<TriangleMesh>& meshes = scene.meshes.edit();
  for (size_t i = first; i < meshes.size(); ++i) {
    TriangleMesh& mesh = meshes[i];
    if (const uint64_t open = openEdgeCount(mesh); open > 0 || mesh.triangles.empty()) {
      const std::string name = mesh.name.empty() ? "" : " \"" + mesh.name + "\"";
      object.child("medium").fail(fmt::format(
          "a medium fills a closed object, but this object's mesh{} is open ({} edges not shared by exactly two "
          "triangles of opposite orientation)", name, open));
    }
    mesh.media.inside = medium;
  }
  if (object.has("material")) return;
  for (size_t i = first; i < meshes.size(); ++i) scene.boundaryMeshes.push_back(std::move(meshes[i]));
  meshes.resize(first);
}

void readSceneMedium(const JsonNode& root, Scene& scene) {
  auto given = [&](const char* section) {
    return root.has(section) && root.child(section).value().is_object() && root.child(section).has("medium");
  };
  if (given("render") && given("environment")) {
    root.child("environment").child("medium").fail("the scene's medium is given twice: keep render.medium or this");
  }
  if (given("render")) scene.sceneMedium = resolveMedium(root.child("render").child("medium"), scene);
  if (given("environment")) scene.sceneMedium = resolveMedium(root.child("environment").child("medium"), scene);
}

}  // namespace penumbra
