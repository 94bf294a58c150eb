// The "objects" section: spheres stay analytic; meshes (OBJ or glTF, with their
// own materials), quads, boxes and teapots become transformed TriangleMeshes.
#include "io/scene_sections.h"
#include "core/byte_size.h"

#include "io/float_checks.h"
#include "io/media_reader.h"
#include "io/mesh_cleanup.h"
#include "io/load_cache.h"
#include "io/model_import.h"
#include "io/shapes.h"
#include "io/suggest.h"
#include "io/transform.h"

#include <fmt/format.h>
#include <map>
#include <unordered_map>

#if __has_include("io/teapot.h")
#include "io/teapot.h"
#define PENUMBRA_HAS_TEAPOT 1
#else
#define PENUMBRA_HAS_TEAPOT 0
#endif

namespace penumbra {

namespace {

enum class ObjectType { Sphere, Mesh, Quad, Box, Teapot };

// Resolves "material" names to Scene::materials indices.
class MaterialLookup {
 public:
  MaterialLookup(const Scene& scene, bool declared) : declared_(declared) {
    for (size_t i = 0; i < scene.materials.size(); ++i) {
      index_.emplace(scene.materials[i].name, static_cast<int>(i));
      names_.push_back(scene.materials[i].name);
    }
  }

  int resolve(const JsonNode& object, const std::string& why = "") const {
    if (!object.has("material")) {
      // Without a "materials" section every object uses the implicit default.
      if (!declared_) return 0;
      object.fail("missing required key \"material\"" + why);
    }
    JsonNode node = object.child("material");
    std::string name = node.asString();
    auto it = index_.find(name);
    if (it == index_.end()) {
      std::string hint = didYouMean(name, names_);
      node.fail("unknown material " + describeJson(node.value()) + hint);
    }
    return it->second;
  }

 private:
  bool declared_;
  std::unordered_map<std::string, int> index_;
  std::vector<std::string> names_;
};

// A number, or [s, s, s]: a sphere scales uniformly (it has no other shape to keep).
float uniformScale(const JsonNode& node) {
  if (node.value().is_number()) return node.asFloat(Range::above(0.0));
  const Vec3 v = node.asVec3();
  if (!(v.x > 0.0f) || v.x != v.y || v.x != v.z) node.fail("a sphere scales uniformly: one number > 0");
  return v.x;
}

Sphere readSphere(const JsonNode& node) {
  node.allowKeys({"type", "center", "radius", "material", "medium", "translate", "scale"});
  Sphere s;
  s.center = readPosition(node.required("center", " for a sphere"));
  JsonNode radius = node.required("radius", " for a sphere");
  s.radius = radius.asFloat(Range::above(0.0));
  // Like a mesh's transform: scale about the origin, then translate.
  if (node.has("scale")) {
    const float k = uniformScale(node.child("scale"));
    s.center *= k;
    s.radius *= k;
  }
  if (node.has("translate")) s.center += node.child("translate").asVec3();
  checkPositions(radius, {s.center - Vec3(s.radius), s.center + Vec3(s.radius)},
                 "center +- radius");
  return s;
}

TriangleMesh readQuad(const JsonNode& node) {
  Vec3 corner = node.required("corner", " for a quad").asVec3();
  Vec3 edge1 = node.required("edge1", " for a quad").asVec3();
  JsonNode edge2Node = node.required("edge2", " for a quad");
  Vec3 edge2 = edge2Node.asVec3();
  // In double: the float cross product's squared length overflows for edges beyond ~1e9.
  const double length = glm::length(glm::cross(glm::dvec3(edge1), glm::dvec3(edge2)));
  if (!(length > 0.0) || !(length < 1e38)) {
    edge2Node.fail("edge1 and edge2 must be non-zero and not parallel");
  }
  return makeQuad(corner, edge1, edge2);
}

TriangleMesh readBox(const JsonNode& node) {
  Vec3 lo = node.required("min", " for a box").asVec3();
  JsonNode maxNode = node.required("max", " for a box");
  Vec3 hi = maxNode.asVec3();
  if (!(lo.x < hi.x && lo.y < hi.y && lo.z < hi.z)) {
    maxNode.fail("must be greater than min on every axis");
  }
  return makeBox(lo, hi);
}

// A mesh object: its file's materials (MTL, glTF) unless the object names one; faces
// without a material take the scene's (or the implicit default).
// What a mesh holds in memory: vertices with their normals, uvs and colours, and triangles.
uint64_t bytesOf(const TriangleMesh& m) {
  return m.positions.size() * sizeof(Vec3) + m.normals.size() * sizeof(Vec3) + m.uvs.size() * sizeof(Vec2) +
         m.tangents.size() * sizeof(m.tangents[0]) + m.colors.size() * sizeof(m.colors[0]) +
         m.triangles.size() * sizeof(m.triangles[0]);
}

// The scene's meshes from index `first` on.
uint64_t meshBytes(const Scene& scene, size_t first) {
  uint64_t bytes = 0;
  for (size_t i = first; i < scene.meshes.size(); ++i) bytes += bytesOf(scene.meshes[i]);
  return bytes;
}

// Meshes already made in this scene: a model file (by resolved path) or a teapot (by
// subdivisions) placed many times is read or tessellated once, and each placement
// copies it.
struct MeshCache {
  std::map<std::string, LoadedModel> models;
  std::map<int, TriangleMesh> teapots;
};

// A mesh object's model, loaded (its files becoming scene inputs) on first use.
const LoadedModel& cachedModel(const JsonNode& fileNode, const std::string& file, MeshCache& cache, Scene& scene) {
  const std::string path = resolvePath(fileNode, file);
  auto cached = cache.models.find(path);
  if (cached == cache.models.end()) {
    try {
      cached = cache.models.emplace(path, loadModelFor(fileNode.context(), path)).first;
    } catch (const ModelError& e) {
      fileNode.fail(e.what());
    }
    scene.inputs.insert(scene.inputs.end(), cached->second.files.begin(), cached->second.files.end());
  }
  return cached->second;
}

void readModelObject(const JsonNode& node, const MaterialLookup& materials, MeshCache& cache, Scene& scene) {
  JsonNode fileNode = node.required("file", " for a mesh (an OBJ or glTF path)");
  std::string file = fileNode.asString();
  if (file.empty()) fileNode.fail("must not be empty");
  const int named = node.has("material") ? materials.resolve(node) : -1;
  const Transform transform = readTransform(node);
  LoadedModel model = cachedModel(fileNode, file, cache, scene);  // moved into the scene: a copy
  // A medium's boundary (a medium, no material) is invisible: its faces need no material.
  const bool boundary = node.has("medium") && !node.has("material");
  int fallback = boundary ? 0 : -1;
  for (const TriangleMesh& mesh : model.meshes) {
    if (named >= 0 || mesh.material >= 0 || boundary) continue;
    const std::string why = model.materials.empty()
        ? " (" + file + " has no materials" + (model.warning.empty() ? "" : ": " + model.warning) + ")"
        : " (some faces of " + file + " have no material)";
    fallback = materials.resolve(node, why);
    break;
  }
  addModelMeshes(fileNode, model, named, fallback, transform, scene);
}

TriangleMesh readTeapot(const JsonNode& node, MeshCache& cache) {
  int subdivisions = node.intOr("subdivisions", 8, 1, 128);
#if PENUMBRA_HAS_TEAPOT
  auto cached = cache.teapots.find(subdivisions);
  if (cached == cache.teapots.end()) cached = cache.teapots.emplace(subdivisions, makeTeapot(subdivisions)).first;
  TriangleMesh mesh = cached->second;
  if (mesh.name.empty()) mesh.name = "teapot";
  return mesh;
#else
  (void)subdivisions;
  node.fail("this build has no teapot support (io/teapot.h is missing)");
#endif
}

// What a mesh or teapot object will add to the scene's meshes, before it is built:
// its model's bytes (loading the file into the cache) or the teapot's grid; 0 for
// small primitives and for an object readObject will refuse anyway.
uint64_t predictedBytes(const JsonNode& node, MeshCache& cache, Scene& scene) {
  const nlohmann::json& v = node.value();
  if (!v.is_object() || !v.contains("type") || !v["type"].is_string()) return 0;
  const std::string type = v["type"].get<std::string>();
  if (type == "teapot") {
    const int64_t n = v.contains("subdivisions") && v["subdivisions"].is_number_integer()
                          ? v["subdivisions"].get<int64_t>() : v.contains("subdivisions") ? 0 : 8;
    if (n < 1 || n > 128) return 0;
    const uint64_t grid = uint64_t(n + 1) * uint64_t(n + 1);
    return 32 * (grid * (sizeof(Vec3) * 2 + sizeof(Vec2)) + uint64_t(2 * n * n) * 12);  // 32 patches
  }
  if (type == "mesh" && v.contains("file") && v["file"].is_string() && !v["file"].get<std::string>().empty()) {
    uint64_t total = 0;
    for (const TriangleMesh& m : cachedModel(node.child("file"), v["file"].get<std::string>(), cache, scene).meshes) {
      total += bytesOf(m);
    }
    return total;
  }
  return 0;
}

void readObject(const JsonNode& node, const MaterialLookup& materials, MeshCache& cache, Scene& scene) {
  node.requireObject();
  auto type = static_cast<ObjectType>(
      node.required("type", " (\"sphere\", \"mesh\", \"quad\", \"box\" or \"teapot\")")
          .asEnum({"sphere", "mesh", "quad", "box", "teapot"}));
  // Its inside's medium (media_reader.h); with no material, the object is only that
  // medium's invisible boundary.
  const int medium = objectMedium(node, scene);
  const bool boundary = medium != kNoMedium && !node.has("material");
  const size_t firstMesh = scene.meshes.size();
  if (type == ObjectType::Mesh) {
    node.allowKeys({"type", "file", "material", "medium", "translate", "rotate", "scale"});
    readModelObject(node, materials, cache, scene);
    placeMediumMeshes(node, medium, scene, firstMesh);
    return;
  }
  if (type == ObjectType::Sphere) {
    Sphere sphere = readSphere(node);
    sphere.media.inside = medium;
    sphere.material = boundary ? -1 : materials.resolve(node);
    if (boundary) {
      scene.boundarySpheres.push_back(sphere);
      return;
    }
    if (maxComponent(scene.materials[sphere.material].emission) > 0.0f) {
      node.child("material").fail("an emitting material on a sphere object is not supported (use a sphere light)");
    }
    scene.spheres.push_back(sphere);
    return;
  }
  switch (type) {
    case ObjectType::Quad:
      node.allowKeys({"type", "corner", "edge1", "edge2", "material", "medium", "translate", "rotate", "scale"});
      break;
    case ObjectType::Box:
      node.allowKeys({"type", "min", "max", "material", "medium", "translate", "rotate", "scale"});
      break;
    default:
      node.allowKeys({"type", "subdivisions", "material", "medium", "translate", "rotate", "scale"});
      break;
  }
  // Check cheap fields before an expensive OBJ load or tessellation.
  int material = boundary ? -1 : materials.resolve(node);
  Transform transform = readTransform(node);
  TriangleMesh mesh = type == ObjectType::Quad ? readQuad(node)
                      : type == ObjectType::Box  ? readBox(node)
                                                 : readTeapot(node, cache);
  applyTransform(transform, mesh);
  checkPositions(node, mesh.positions, "transformed positions");
  // Triangles whose normal cannot be computed in float (zero area, or a scale so
  // small the cross product underflows) would hit with NaN normals: drop them.
  if (dropDegenerateTriangles(mesh) > 0 && mesh.triangles.empty()) {
    node.fail("every triangle has zero area after the transform (is the scale too small?)");
  }
  mesh.material = material;
  scene.meshes.push_back(std::move(mesh));
  placeMediumMeshes(node, medium, scene, firstMesh);
}

}  // namespace

void readObjects(const JsonNode& root, Scene& scene) {
  if (!root.has("objects")) return;
  MaterialLookup materials(scene, root.has("materials"));
  JsonNode objects = root.child("objects");
  size_t count = objects.arraySize();
  MeshCache cache;
  const LoadLimits& limits = root.context().limits;
  uint64_t bytes = meshBytes(scene, 0);
  for (size_t i = 0; i < count; ++i) {
    // Instances add up: refuse at the object that would take the meshes past the
    // budget, judged before it is built (the bytes its cached model or tessellation takes).
    const JsonNode object = objects.element(i);
    const uint64_t adds = predictedBytes(object, cache, scene);
    if (limits.maxBytes > 0 && bytes + adds > limits.maxBytes) {
      object.fail(fmt::format("the scene's meshes would reach ~{} with this object, but {} is {}",
                              formatBytes(double(bytes + adds)), limits.budgetName, formatBytes(double(limits.maxBytes))));
    }
    const size_t before = scene.meshes.size();
    readObject(object, materials, cache, scene);
    bytes += meshBytes(scene, before);
  }
}

}  // namespace penumbra
