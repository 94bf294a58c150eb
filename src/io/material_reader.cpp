// The "materials" section: Phong terms, mirror and glass parameters, photon
// Russian-roulette probabilities, the textures materials reference, normal maps and
// alpha cut-outs.
#include "io/scene_sections.h"
#include "io/load_cache.h"
#include "io/input_file.h"
#include "core/color.h"
#include "io/alpha_mask_reader.h"
#include "io/float_checks.h"
#include "io/texture_check.h"

#include <cstdio>
#include <filesystem>
#include <map>

namespace penumbra {

namespace {

namespace fs = std::filesystem;

// Texture paths of this form name a procedural texture instead of a file.
// They are stored verbatim in Texture::path; the name and width are checked
// here, and the pipeline generates (or reuses) the image from its cache.
constexpr const char* kBuiltinPrefix = "builtin:";

// (path, data) -> index into Scene::textures, so materials sharing a file share it;
// the same file read as colours and as data is two textures.
using TextureIndex = std::map<std::pair<std::string, bool>, int>;

// A texture file (or "builtin:NAME") by path: its Scene::textures index, decoded once.
int textureIndex(const JsonNode& fileNode, bool data, Scene& scene, TextureIndex& index);

int readTexture(const JsonNode& node, Material& material, Scene& scene, TextureIndex& index) {
  node.allowKeys({"file", "blend", "uv_scale"});
  // Repeats across (u, v): a number for both, or [u, v].
  if (node.has("uv_scale")) {
    const JsonNode scale = node.child("uv_scale");
    const Range positive = Range::above(0.0);
    if (scale.value().is_number()) {
      material.uvScale = Vec2(scale.asFloat(positive));
    } else if (scale.arraySize() == 2) {
      material.uvScale = Vec2(scale.element(0).asFloat(positive), scale.element(1).asFloat(positive));
    } else {
      scale.fail("must be a number or [u, v]");
    }
    // Bounded as texture coordinates are, so uv x uv_scale stays a finite float.
    const float most = static_cast<float>(kMaxTexCoord);
    if (material.uvScale.x > most || material.uvScale.y > most) scale.fail("must be <= 1e6");
  }
  size_t blend = node.enumOr("blend", 0, {"multiply", "add"});
  material.textureBlend = blend == 0 ? TextureBlend::Multiply : TextureBlend::Add;
  return textureIndex(node.required("file", " (an image path or \"builtin:NAME\")"), false, scene, index);
}

int textureIndex(const JsonNode& fileNode, bool data, Scene& scene, TextureIndex& index) {
  std::string file = fileNode.asString();
  if (file.empty()) fileNode.fail("must not be empty");
  std::string path;
  const bool builtin = file.rfind(kBuiltinPrefix, 0) == 0;
  if (builtin) {
    if (file.size() == std::char_traits<char>::length(kBuiltinPrefix)) {
      fileNode.fail("builtin texture needs a name, e.g. \"builtin:checker\"");
    }
    path = file;
  } else {
    path = resolvePath(fileNode, file);
    if (const std::string why = unreadableFileReason(path); !why.empty()) fileNode.fail("texture file " + path + ": " + why);
  }
  auto [it, inserted] = index.try_emplace({path, data}, static_cast<int>(scene.textures.size()));
  if (inserted) {
    // Decoded now, once per file: a truncated image must fail here, not render black.
    const std::string problem = builtin ? builtinTextureProblem(file) : textureProblemFor(fileNode.context(), path);
    if (!problem.empty()) fileNode.fail(problem);
    scene.textures.push_back(Texture{path, data, std::nullopt});
    if (!builtin) scene.inputs.push_back(path);
  }
  return it->second;
}

// A tangent-space normal map (data, with glTF's scale) and the cut-out: alpha_mode
// "mask" (the default with alpha_texture) keeps alpha >= alpha_cutoff, "blend" keeps
// a hit with probability alpha; alpha_texture's alpha channel (or its grey) times alpha.
void readNormalAndAlpha(const JsonNode& node, Material& m, Scene& scene, TextureIndex& textures) {
  if (node.has("normal_texture")) m.normalTexture = textureIndex(node.child("normal_texture"), true, scene, textures);
  m.normalScale = node.floatOr("normal_scale", m.normalScale, Range::between(-1e3, 1e3));
  const Range unit = Range::between(0.0, 1.0);
  m.alpha = node.floatOr("alpha", m.alpha, unit);
  m.alphaCutoff = node.floatOr("alpha_cutoff", m.alphaCutoff, unit);
  const size_t fallback = node.has("alpha_texture") || node.has("alpha_cutoff") ? 1 : node.has("alpha") ? 2 : 0;
  m.alphaMode = static_cast<AlphaMode>(node.enumOr("alpha_mode", fallback, {"opaque", "mask", "blend"}));
  if (node.has("alpha_texture")) {
    const JsonNode file = node.child("alpha_texture");
    if (file.asString().empty()) file.fail("must not be empty");
    const std::string path = resolvePath(file, file.asString());
    if (const std::string why = unreadableFileReason(path); !why.empty()) file.fail("texture file " + path + ": " + why);
    m.alphaMask = addAlphaMask(file, path, scene, true);
  }
}

Material readMaterial(const JsonNode& node, const std::string& name, Scene& scene,
                      TextureIndex& textures) {
  node.allowKeys({"ambient", "diffuse", "specular", "shininess", "reflective", "transparent",
                  "p_r", "p_t", "texture", "emission", "emission_texture", "metallic", "roughness", "metallic_roughness_texture",
                  "normal_texture", "normal_scale", "alpha", "alpha_mode", "alpha_cutoff", "alpha_texture"});
  Material m;
  m.name = name;
  m.ambient = node.colorOr("ambient", m.ambient);
  m.diffuse = node.colorOr("diffuse", m.diffuse);
  m.specular = node.colorOr("specular", m.specular);
  m.shininess = node.floatOr("shininess", m.shininess, Range::atLeast(0.0));
  // An emitting material makes its meshes one area light (addMeshEmitters).
  m.emission = node.colorOr("emission", m.emission);
  if (node.has("emission_texture")) {
    const JsonNode file = node.child("emission_texture");
    if (!(maxComponent(m.emission) > 0.0f)) file.fail("needs an emission above 0 (the texture multiplies it)");
    m.emissionTexture = textureIndex(file, false, scene, textures);
  }
  const Range unit = Range::between(0.0, 1.0);
  if (node.has("reflective")) {
    JsonNode reflective = node.child("reflective");
    reflective.allowKeys({"kr"});
    m.kr = reflective.required("kr", " (mirror weight 0..1)").asFloat(unit);
  }
  if (node.has("transparent")) {
    JsonNode transparent = node.child("transparent");
    transparent.allowKeys({"ior", "tint"});
    m.transparent = true;
    m.ior = transparent.floatOr("ior", m.ior, Range::between(kMinIor, kMaxIor));
    m.tint = transparent.colorOr("tint", m.tint);
  }
  // glTF's metallic-roughness: `diffuse` is the base colour. A mirror is roughness 0.
  m.metalRough = node.has("metallic") || node.has("roughness") || node.has("metallic_roughness_texture");
  if (m.metalRough) {
    for (const char* key : {"reflective", "specular", "shininess"}) {
      if (node.has(key)) {
        node.child(key).fail("is a Phong term; a metallic-roughness material (metallic, roughness) has none");
      }
    }
    m.metallic = node.floatOr("metallic", 0.0f, unit);
    m.roughness = node.floatOr("roughness", 0.5f, unit);
    m.specular = Color(0.0f);
    m.shininess = 0.0f;
  }
  // Photon probabilities default to what the shading does: reflect as often as
  // the mirror weight, transmit the remainder filtered by the tint's mean.
  m.pR = node.floatOr("p_r", m.kr, unit);
  float defaultPT = 0.0f;
  if (m.transparent) {
    float meanTint = meanOf(m.tint);
    defaultPT = std::clamp((1.0f - m.pR) * meanTint, 0.0f, 1.0f - m.pR);
  }
  m.pT = node.floatOr("p_t", defaultPT, unit);
  if (m.pR + m.pT > 1.0f + 1e-6f) {
    char buf[128];
    std::snprintf(buf, sizeof buf, "p_r + p_t must be <= 1, got %g + %g = %g", m.pR, m.pT,
                  m.pR + m.pT);
    node.fail(buf);
  }
  const bool bounded = boundsAlbedo(modelOf(scene.render).bsdf);
  if (bounded && m.transparent) {
    // A transmittance filter above 1 would add light at every crossing.
    if (maxComponent(m.tint) > 1.0f + 1e-6f) {
      node.child("transparent").child("tint").fail("must be <= 1 in the physical model");
    }
  } else if (bounded) {
    // A physical surface may not reflect more than arrives: rho_d + rho_s <= 1
    // (the glossy lobe exists only with shininess > 0).
    for (int c = 0; c < 3; ++c) {
      float sum = m.diffuse[c] + (m.shininess > 0.0f ? m.specular[c] : 0.0f);
      if (sum > 1.0f + 1e-6f) {
        char buf[160];
        std::snprintf(buf, sizeof buf,
                      "diffuse + specular must be <= 1 in the physical model, got %g + %g = %g "
                      "in channel %d",
                      m.diffuse[c], m.specular[c], sum, c);
        node.fail(buf);
      }
    }
  }
  if (node.has("texture")) m.texture = readTexture(node.child("texture"), m, scene, textures);
  if (node.has("metallic_roughness_texture")) {
    m.metalRoughTexture = textureIndex(node.child("metallic_roughness_texture"), true, scene, textures);
  }
  readNormalAndAlpha(node, m, scene, textures);
  return m;
}

}  // namespace

std::string resolvePath(const JsonNode& where, const std::string& file) {
  fs::path p(file);
  if (p.is_relative()) p = where.context().baseDir / p;
  return p.lexically_normal().string();
}

void readMaterials(const JsonNode& root, Scene& scene) {
  if (!root.has("materials")) {
    Material fallback;
    fallback.name = "default";
    scene.materials.push_back(fallback);
    return;
  }
  JsonNode materials = root.child("materials");
  TextureIndex textures;
  for (const std::string& name : materials.keys()) {
    scene.materials.push_back(readMaterial(materials.child(name), name, scene, textures));
  }
}

}  // namespace penumbra
