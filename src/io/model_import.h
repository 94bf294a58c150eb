// What a model file (OBJ + MTL, glTF) brings into a scene: meshes with their own
// materials, and for glTF a camera and lights. Shared by the "mesh" object and
// by a glTF file loaded as the whole scene.
#pragma once
#include "core/scene.h"
#include "io/gltf_cameras.h"
#include "io/load_limits.h"
#include <stdexcept>
#include <string>
#include <vector>

namespace penumbra {

class JsonNode;
struct Transform;

// Why a model file could not be used; the scene loader adds the scene file and
// JSON path in front of the message.
class ModelError : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

// A material from the file, mapped onto penumbra's (docs/scene-format.md says what
// is approximated); `texture` is the absolute path of its diffuse (base colour) map,
// "" = none.
struct ModelMaterial {
  Material material;
  std::string texture;
  std::string metalRoughTexture;  // glTF's metallicRoughnessTexture, "" = none
  std::string normalTexture;      // tangent-space normal map (glTF normalTexture, MTL norm/bump)
  std::string alphaTexture;       // the image whose alpha channel cuts out (glTF: the base colour's)
  std::string emissionTexture;    // times the emission (glTF emissiveTexture, MTL map_Ke)
  // Each map's own sampler (glTF; the alpha mask reads the base colour's), absent =
  // the scene file's rule (OBJ).
  std::optional<TextureSampling> textureSampler, metalRoughSampler, normalSampler, emissionSampler;
};

struct LoadedModel {
  std::string file;                        // for material names and messages
  std::vector<TriangleMesh> meshes;        // material = index into `materials`, -1 = none
  std::vector<ModelMaterial> materials;
  std::vector<GltfCamera> cameras;         // glTF: the file's cameras, by index (io/gltf_cameras.h)
  std::vector<Light> lights;               // glTF: KHR_lights_punctual
  std::string warning;                     // the loader's first warning (a missing MTL file)
  std::vector<std::string> ignoredExtensions;  // glTF: optional extensions penumbra does not read
  std::vector<std::string> files;          // every file read: the model, MTLs, buffers, images
};

// Loads an OBJ (+ MTL) or glTF file by its extension (.obj, .gltf, .glb). Throws
// ModelError.
LoadedModel loadModel(const std::string& path, const LoadLimits& limits = {});
bool isGltfPath(const std::string& path);
// A model file a scene path may name instead of a JSON scene: .gltf, .glb or .obj.
bool isModelPath(const std::string& path);

// Adds the model's meshes to `scene`: each gets `named` when >= 0 (the scene names
// the material), else its own material (appended to Scene::materials as
// "file:name", checked for the shading model: the physical model's energy limits,
// textures decoded at load) or `fallback` for faces without one. `transform` applies
// on top of the file's own (glTF node) transforms; positions are checked and
// degenerate triangles dropped. Fails at `where` when nothing is left. The model's
// warning and the extensions it leaves unread become notes in scene.load (each once).
void addModelMeshes(const JsonNode& where, LoadedModel& model, int named, int fallback,
                    const Transform& transform, Scene& scene);

// Scene::textures' index for an image file read with `sampler` (shared when already
// there), decoded once now; fails at `where` naming the problem.
int addTextureFile(const JsonNode& where, const std::string& path, Scene& scene, bool data = false,
                   const std::optional<TextureSampling>& sampler = std::nullopt);

}  // namespace penumbra
