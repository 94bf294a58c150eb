// glTF materials: metallic-roughness (base colour, metallic, roughness and their
// textures, KHR_materials_ior), transmission + ior as glass, emissive (factor, texture,
// strength, doubleSided) as emission, the normal map and alphaMode.
#include "io/gltf_materials.h"

#include "io/gltf_files.h"
#include "io/gltf_samplers.h"
#include "io/temp_file.h"
#include "io/texture_gen.h"
#include "core/error.h"

#include <algorithm>
#include <cmath>

namespace penumbra {

namespace {

namespace fs = std::filesystem;

double extensionNumber(const tinygltf::ExtensionMap& ext, const char* name, const char* key, double fallback) {
  auto it = ext.find(name);
  if (it == ext.end() || !it->second.Has(key)) return fallback;
  const tinygltf::Value& v = it->second.Get(key);
  return v.IsNumber() || v.IsInt() ? v.GetNumberAsDouble() : fallback;
}

// A number list from an extension object (`fallback` when absent or malformed).
std::vector<double> extensionNumbers(const tinygltf::ExtensionMap& ext, const char* name, const char* key,
                                     std::vector<double> fallback) {
  auto it = ext.find(name);
  if (it == ext.end() || !it->second.Has(key) || !it->second.Get(key).IsArray()) return fallback;
  const tinygltf::Value& v = it->second.Get(key);
  std::vector<double> out;
  for (size_t i = 0; i < v.ArrayLen(); ++i) {
    if (!v.Get(int(i)).IsNumber() && !v.Get(int(i)).IsInt()) return fallback;
    out.push_back(v.Get(int(i)).GetNumberAsDouble());
  }
  return out.size() == fallback.size() ? out : fallback;
}

// KHR_texture_transform of the base colour's texture: every map of the material
// follows it (penumbra keeps one placement per material).
void readTextureTransform(const tinygltf::TextureInfo& info, Material& m) {
  const char* ext = "KHR_texture_transform";
  const std::vector<double> scale = extensionNumbers(info.extensions, ext, "scale", {1.0, 1.0});
  const std::vector<double> offset = extensionNumbers(info.extensions, ext, "offset", {0.0, 0.0});
  m.uvScale = Vec2(float(scale[0]), float(scale[1]));
  m.uvOffset = Vec2(float(offset[0]), float(offset[1]));
  // Any finite angle is valid (checkGltfMaterial bounded the rest): reduced in double,
  // as a float 1e39 would be inf and its cosine NaN.
  m.uvRotation = float(std::remainder(extensionNumber(info.extensions, ext, "rotation", 0.0), 2.0 * M_PI));
}

Color colour(const std::vector<double>& c, const Color& fallback) {
  return c.size() >= 3 ? Color(float(c[0]), float(c[1]), float(c[2])) : fallback;
}

// An embedded image (data URI or buffer view) as a file OpenImageIO's texture system
// can open: written once to the texture cache under a name from its content.
std::string writeEmbedded(const tinygltf::Image& image, const std::string& path) {
  uint64_t h = 1469598103934665603ull;  // FNV-1a over the encoded bytes
  for (unsigned char b : image.image) h = (h ^ b) * 1099511628211ull;
  const bool png = image.image.size() > 4 && image.image[0] == 0x89 && image.image[1] == 'P';
  char name[64];
  std::snprintf(name, sizeof name, "gltf-%016llx.%s", static_cast<unsigned long long>(h), png ? "png" : "jpg");
  const fs::path dir = textureCacheDirectory();
  std::error_code ec;
  fs::create_directories(dir, ec);
  const fs::path file = dir / name;
  if (fs::is_regular_file(file, ec) && fs::file_size(file, ec) == image.image.size()) return file.string();
  try {
    writeFileAtomic(file.string(), image.image.data(), image.image.size(), "embedded image");
  } catch (const InputError& e) {
    throw ModelError("glTF file " + path + ": cannot write its embedded image to " + dir.string() + " (" + e.what() + ")");
  }
  return file.string();
}

// The file behind texture `index` ("" without one).
std::string textureFile(const tinygltf::Model& model, int index, const std::string& path, const std::string& folder) {
  if (index < 0) return "";
  if (static_cast<size_t>(index) >= model.textures.size()) {
    throw ModelError("glTF file " + path + ": texture " + std::to_string(index) + " does not exist");
  }
  const int source = model.textures[index].source;
  if (source < 0 || static_cast<size_t>(source) >= model.images.size()) {
    throw ModelError("glTF file " + path + ": texture " + std::to_string(index) + " has no image");
  }
  const tinygltf::Image& image = model.images[source];
  if (!image.uri.empty() && image.uri.rfind("data:", 0) != 0) {
    // The file tinygltf read, inside the model's folder (gltf_files.h).
    return resolveGltfUri(folder, image.uri, "images[" + std::to_string(source) + "].uri", path);
  }
  if (image.image.empty()) throw ModelError("glTF file " + path + ": image " + std::to_string(source) + " is empty");
  return writeEmbedded(image, path);
}

}  // namespace

bool keepEncodedImage(tinygltf::Image* image, const int, std::string*, std::string*, int, int,
                      const unsigned char* bytes, int size, void*) {
  image->image.assign(bytes, bytes + size);
  return true;
}

std::vector<ModelMaterial> gltfMaterials(const tinygltf::Model& model, const std::string& path,
                                         const std::string& folder) {
  std::vector<ModelMaterial> out;
  for (const tinygltf::Material& g : model.materials) {
    ModelMaterial mm;
    Material& m = mm.material;
    m.name = g.name.empty() ? "material " + std::to_string(out.size()) : g.name;
    const tinygltf::PbrMetallicRoughness& pbr = g.pbrMetallicRoughness;
    const Color base = colour(pbr.baseColorFactor, Color(1.0f));
    const float metallic = std::clamp(float(pbr.metallicFactor), 0.0f, 1.0f);
    const float roughness = std::clamp(float(pbr.roughnessFactor), 0.0f, 1.0f);
    const float transmission =
        float(extensionNumber(g.extensions, "KHR_materials_transmission", "transmissionFactor", 0.0));
    const float strength =
        float(extensionNumber(g.extensions, "KHR_materials_emissive_strength", "emissiveStrength", 1.0));
    // Emission adds to the surface's BSDF (glTF's model), on the front only unless
    // the material is double-sided.
    m.emission = colour(g.emissiveFactor, Color(0.0f)) * strength;
    m.emitterShades = true;
    m.twoSidedEmission = g.doubleSided;
    mm.emissionTexture = textureFile(model, g.emissiveTexture.index, path, folder);
    mm.emissionSampler = gltfTextureSampling(model, g.emissiveTexture.index, path);
    m.ambient = Color(0.1f) * base;
    if (transmission >= 0.5f) {
      // Glass: smooth, the base colour as its transmission filter.
      m.transparent = true;
      m.ior = float(extensionNumber(g.extensions, "KHR_materials_ior", "ior", 1.5));
      // KHR_materials_volume: Beer-Lambert through its thickness, as one filter.
      const double thickness = extensionNumber(g.extensions, "KHR_materials_volume", "thicknessFactor", 0.0);
      const double distance = extensionNumber(g.extensions, "KHR_materials_volume", "attenuationDistance", 0.0);
      const std::vector<double> attenuation =
          extensionNumbers(g.extensions, "KHR_materials_volume", "attenuationColor", {1.0, 1.0, 1.0});
      Color volume(1.0f);
      if (thickness > 0.0 && distance > 0.0 && std::isfinite(distance)) {
        for (int c = 0; c < 3; ++c) volume[c] = float(std::pow(std::clamp(attenuation[c], 0.0, 1.0), thickness / distance));
      }
      m.tint = base * volume;
      m.diffuse = m.specular = Color(0.0f);
      m.shininess = 0.0f;
    } else {
      // glTF's own model: the base colour, metallic and roughness (factor times the
      // texture's B and G), and KHR_materials_ior's index for the dielectric's F0.
      m.metalRough = true;
      m.diffuse = base;
      m.specular = Color(0.0f);
      m.shininess = 0.0f;
      m.metallic = metallic;
      m.roughness = roughness;
      m.ior = float(extensionNumber(g.extensions, "KHR_materials_ior", "ior", 1.5));
      mm.texture = textureFile(model, pbr.baseColorTexture.index, path, folder);
      mm.textureSampler = gltfTextureSampling(model, pbr.baseColorTexture.index, path);
      readTextureTransform(pbr.baseColorTexture.index >= 0 ? pbr.baseColorTexture : pbr.metallicRoughnessTexture, m);
      mm.metalRoughTexture = textureFile(model, pbr.metallicRoughnessTexture.index, path, folder);
      mm.metalRoughSampler = gltfTextureSampling(model, pbr.metallicRoughnessTexture.index, path);
    }
    // The tangent-space normal map and the cut-out: alphaMode reads the base colour's
    // alpha (factor times the base texture's alpha channel, decoded at load).
    mm.normalTexture = textureFile(model, g.normalTexture.index, path, folder);
    mm.normalSampler = gltfTextureSampling(model, g.normalTexture.index, path);
    m.normalScale = float(g.normalTexture.scale);
    m.alphaMode = g.alphaMode == "MASK" ? AlphaMode::Mask : g.alphaMode == "BLEND" ? AlphaMode::Blend : AlphaMode::Opaque;
    m.alpha = pbr.baseColorFactor.size() >= 4 ? float(pbr.baseColorFactor[3]) : 1.0f;
    m.alphaCutoff = float(g.alphaCutoff);
    if (m.alphaMode != AlphaMode::Opaque) {
      mm.alphaTexture = textureFile(model, pbr.baseColorTexture.index, path, folder);
      mm.textureSampler = gltfTextureSampling(model, pbr.baseColorTexture.index, path);
    }
    out.push_back(std::move(mm));
  }
  return out;
}

}  // namespace penumbra
