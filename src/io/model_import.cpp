// Model files into the scene: their materials made valid for the shading model,
// their textures checked, their meshes transformed and bound to materials.
#include "io/model_import.h"
#include "io/load_cache.h"
#include "io/input_file.h"

#include "core/color.h"
#include "io/alpha_mask_reader.h"
#include "io/float_checks.h"
#include "io/gltf_loader.h"
#include "io/json_reader.h"
#include "io/mesh_cleanup.h"
#include "io/obj_loader.h"
#include "io/texture_check.h"
#include "io/transform.h"

#include <algorithm>
#include <cmath>
#include <filesystem>

namespace penumbra {

namespace {

std::string lowerExtension(const std::string& path) {
  std::string ext = std::filesystem::path(path).extension().string();
  std::transform(ext.begin(), ext.end(), ext.begin(), [](unsigned char c) { return std::tolower(c); });
  return ext;
}

// The same limits the JSON materials meet (material_reader.cpp): radiometric BSDFs
// (the physical model's) reflect at most what arrives and glass filters never amplify,
// so specular gives way to diffuse and tints are clamped to 1; classic photon roulette
// follows the shading as its defaults do.
// A value the file gave as NaN (an MTL "Kd nan") counts as 0, never reaches a ray.
float bounded(float v, float lo, float hi) { return std::isnan(v) ? lo : std::clamp(v, lo, hi); }

Material fitToModel(Material m, BsdfFamily family) {
  for (Color* c : {&m.ambient, &m.diffuse, &m.specular, &m.emission, &m.tint}) {
    for (int k = 0; k < 3; ++k) (*c)[k] = bounded((*c)[k], 0.0f, 1e30f);
  }
  m.shininess = bounded(m.shininess, 0.0f, 1e30f);
  m.kr = bounded(m.kr, 0.0f, 1.0f);
  m.metallic = bounded(m.metallic, 0.0f, 1.0f);
  m.roughness = bounded(m.roughness, 0.0f, 1.0f);
  m.ior = std::isnan(m.ior) ? 1.5f : std::clamp(m.ior, 0.01f, 100.0f);
  m.alpha = bounded(m.alpha, 0.0f, 1.0f);
  m.alphaCutoff = bounded(m.alphaCutoff, 0.0f, 1.0f);
  m.normalScale = std::isfinite(m.normalScale) ? std::clamp(m.normalScale, -1e3f, 1e3f) : 1.0f;
  if (boundsAlbedo(family)) {
    m.diffuse = glm::min(m.diffuse, Color(1.0f));
    if (m.shininess > 0.0f) m.specular = glm::min(m.specular, Color(1.0f) - m.diffuse);
    m.tint = glm::min(m.tint, Color(1.0f));
  }
  m.pR = m.kr;
  m.pT = m.transparent ? std::clamp((1.0f - m.pR) * meanOf(m.tint), 0.0f, 1.0f - m.pR) : 0.0f;
  return m;
}

}  // namespace

bool isGltfPath(const std::string& path) {
  const std::string ext = lowerExtension(path);
  return ext == ".gltf" || ext == ".glb";
}

bool isModelPath(const std::string& path) { return isGltfPath(path) || lowerExtension(path) == ".obj"; }

LoadedModel loadModel(const std::string& path, const LoadLimits& limits) {
  LoadedModel model = isGltfPath(path) ? loadGltfModel(path, limits) : loadObjModel(path, limits);
  if (model.files.empty() || model.files.front() != path) model.files.insert(model.files.begin(), path);
  return model;
}

int addTextureFile(const JsonNode& where, const std::string& path, Scene& scene, bool data,
                   const std::optional<TextureSampling>& sampler) {
  for (size_t i = 0; i < scene.textures.size(); ++i) {
    if (scene.textures[i] == Texture{path, data, sampler}) return static_cast<int>(i);
  }
  if (const std::string why = unreadableFileReason(path); !why.empty()) where.fail("texture file " + path + ": " + why);
  const std::string problem = textureProblemFor(where.context(), path);
  if (!problem.empty()) where.fail(problem);
  scene.textures.push_back(Texture{path, data, sampler});
  scene.inputs.push_back(path);
  return static_cast<int>(scene.textures.size()) - 1;
}

void addModelMeshes(const JsonNode& where, LoadedModel& model, int named, int fallback,
                    const Transform& transform, Scene& scene) {
  // Only the materials some mesh uses join the scene, in the file's order.
  std::vector<int> index(model.materials.size(), -1);
  const std::string stem = std::filesystem::path(model.file).filename().string();
  for (const TriangleMesh& mesh : model.meshes) {
    if (named >= 0 || mesh.material < 0 || index[mesh.material] >= 0) continue;
    const ModelMaterial& mm = model.materials[mesh.material];
    Material m = fitToModel(mm.material, modelOf(scene.render).bsdf);
    m.name = stem + ":" + mm.material.name;
    if (!mm.texture.empty()) m.texture = addTextureFile(where, mm.texture, scene, false, mm.textureSampler);
    if (!mm.metalRoughTexture.empty()) {
      m.metalRoughTexture = addTextureFile(where, mm.metalRoughTexture, scene, true, mm.metalRoughSampler);
    }
    if (!mm.normalTexture.empty()) m.normalTexture = addTextureFile(where, mm.normalTexture, scene, true, mm.normalSampler);
    if (!mm.alphaTexture.empty()) {
      m.alphaMask = addAlphaMask(where, mm.alphaTexture, scene, false, mm.textureSampler.value_or(TextureSampling{}));
    }
    if (!mm.emissionTexture.empty() && maxComponent(m.emission) > 0.0f) {
      m.emissionTexture = addTextureFile(where, mm.emissionTexture, scene, false, mm.emissionSampler);
    }
    index[mesh.material] = static_cast<int>(scene.materials.size());
    scene.materials.push_back(std::move(m));
  }
  size_t added = 0;
  for (TriangleMesh& mesh : model.meshes) {
    mesh.material = named >= 0 ? named : mesh.material >= 0 ? index[mesh.material] : fallback;
    applyTransform(transform, mesh);
    checkPositions(where, mesh.positions, "transformed positions");
    // Triangles whose normal cannot be computed in float would hit with NaN normals.
    dropDegenerateTriangles(mesh);
    if (mesh.triangles.empty()) continue;
    dropWhiteColors(mesh);
    scene.meshes.push_back(std::move(mesh));
    ++added;
  }
  if (added == 0) {
    where.fail("every triangle of " + model.file + " has zero area after the transform (is the scale too small?)");
  }  // Said once per file, however many objects use it.
  auto note = [&](const std::string& line) {
    std::vector<std::string>& notes = scene.load.notes;
    if (std::find(notes.begin(), notes.end(), line) == notes.end()) notes.push_back(line);
  };
  if (!model.warning.empty()) note(model.file + ": " + model.warning);
  if (!model.ignoredExtensions.empty()) {
    std::string names;
    for (const std::string& e : model.ignoredExtensions) {
      names += (names.empty() ? "" : ", ") + e;
      std::vector<std::string>& all = scene.load.ignoredExtensions;
      if (std::find(all.begin(), all.end(), e) == all.end()) all.push_back(e);
    }
    note(model.file + ": ignores " + names + " (optional)");
  }
}

}  // namespace penumbra
