// The "objects" section: spheres stay analytic; meshes (OBJ or glTF, with their
// own materials), quads, boxes and teapots become transformed TriangleMeshes.
#include "io/scene_sections.h"

#include "io/float_checks.h"
#include "io/mesh_cleanup.h"
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
  node.allowKeys({"type", "center", "radius", "material", "translate", "scale"});
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
// What the scene's meshes from index `first` on hold in memory: vertices with their
// normals and uvs, and triangles.
uint64_t meshBytes(const Scene& scene, size_t first) {
  uint64_t bytes = 0;
  for (size_t i = first; i < scene.meshes.size(); ++i) {
    const TriangleMesh& m = scene.meshes[i];
    bytes += m.positions.size() * sizeof(Vec3) + m.normals.size() * sizeof(Vec3) + m.uvs.size() * sizeof(Vec2) +
             m.triangles.size() * sizeof(m.triangles[0]);
  }
  return bytes;
}

// Model files already read in this scene, by resolved path: a file placed many times
// is read and checked once.
using ModelCache = std::map<std::string, LoadedModel>;

void readModelObject(const JsonNode& node, const MaterialLookup& materials, ModelCache& models, Scene& scene) {
  JsonNode fileNode = node.required("file", " for a mesh (an OBJ or glTF path)");
  std::string file = fileNode.asString();
  if (file.empty()) fileNode.fail("must not be empty");
  const int named = node.has("material") ? materials.resolve(node) : -1;
  const Transform transform = readTransform(node);
  const std::string path = resolvePath(fileNode, file);
  auto cached = models.find(path);
  if (cached == models.end()) {
    try {
      cached = models.emplace(path, loadModel(path, node.context().limits)).first;
    } catch (const ModelError& e) {
      fileNode.fail(e.what());
    }
    scene.inputs.insert(scene.inputs.end(), cached->second.files.begin(), cached->second.files.end());
  }
  LoadedModel model = cached->second;  // placed (moved into the scene) as a copy
  int fallback = -1;
  for (const TriangleMesh& mesh : model.meshes) {
    if (named >= 0 || mesh.material >= 0) continue;
    const std::string why = model.materials.empty()
        ? " (" + file + " has no materials" + (model.warning.empty() ? "" : ": " + model.warning) + ")"
        : " (some faces of " + file + " have no material)";
    fallback = materials.resolve(node, why);
    break;
  }
  addModelMeshes(fileNode, model, named, fallback, transform, scene);
}

TriangleMesh readTeapot(const JsonNode& node) {
  int subdivisions = node.intOr("subdivisions", 8, 1, 128);
#if PENUMBRA_HAS_TEAPOT
  TriangleMesh mesh = makeTeapot(subdivisions);
  if (mesh.name.empty()) mesh.name = "teapot";
  return mesh;
#else
  (void)subdivisions;
  node.fail("this build has no teapot support (io/teapot.h is missing)");
#endif
}

void readObject(const JsonNode& node, const MaterialLookup& materials, ModelCache& models, Scene& scene) {
  node.requireObject();
  auto type = static_cast<ObjectType>(
      node.required("type", " (\"sphere\", \"mesh\", \"quad\", \"box\" or \"teapot\")")
          .asEnum({"sphere", "mesh", "quad", "box", "teapot"}));
  if (type == ObjectType::Mesh) {
    node.allowKeys({"type", "file", "material", "translate", "rotate", "scale"});
    readModelObject(node, materials, models, scene);
    return;
  }
  if (type == ObjectType::Sphere) {
    Sphere sphere = readSphere(node);
    sphere.material = materials.resolve(node);
    if (maxComponent(scene.materials[sphere.material].emission) > 0.0f) {
      node.child("material").fail("an emitting material on a sphere object is not supported (use a sphere light)");
    }
    scene.spheres.push_back(sphere);
    return;
  }
  switch (type) {
    case ObjectType::Quad:
      node.allowKeys({"type", "corner", "edge1", "edge2", "material", "translate", "rotate", "scale"});
      break;
    case ObjectType::Box:
      node.allowKeys({"type", "min", "max", "material", "translate", "rotate", "scale"});
      break;
    default:
      node.allowKeys({"type", "subdivisions", "material", "translate", "rotate", "scale"});
      break;
  }
  // Check cheap fields before an expensive OBJ load or tessellation.
  int material = materials.resolve(node);
  Transform transform = readTransform(node);
  TriangleMesh mesh = type == ObjectType::Quad ? readQuad(node)
                      : type == ObjectType::Box  ? readBox(node)
                                                 : readTeapot(node);
  applyTransform(transform, mesh);
  checkPositions(node, mesh.positions, "transformed positions");
  // Triangles whose normal cannot be computed in float (zero area, or a scale so
  // small the cross product underflows) would hit with NaN normals: drop them.
  if (dropDegenerateTriangles(mesh) > 0 && mesh.triangles.empty()) {
    node.fail("every triangle has zero area after the transform (is the scale too small?)");
  }
  mesh.material = material;
  scene.meshes.push_back(std::move(mesh));
}

}  // namespace

void readObjects(const JsonNode& root, Scene& scene) {
  if (!root.has("objects")) return;
  MaterialLookup materials(scene, root.has("materials"));
  JsonNode objects = root.child("objects");
  size_t count = objects.arraySize();
  ModelCache models;
  const LoadLimits& limits = root.context().limits;
  uint64_t bytes = meshBytes(scene, 0);
  for (size_t i = 0; i < count; ++i) {
    const size_t before = scene.meshes.size();
    readObject(objects.element(i), materials, models, scene);
    // Instances add up: refuse at the object that takes the meshes past the budget,
    // before the next one allocates more.
    bytes += meshBytes(scene, before);
    if (limits.maxBytes > 0 && bytes > limits.maxBytes) {
      objects.element(i).fail(fmt::format("the scene's meshes reach ~{:.1f} GB with this object, but {} is {:.1f} GB",
                                          bytes / 1e9, limits.budgetName, limits.maxBytes / 1e9));
    }
  }
}

}  // namespace penumbra
