// glTF material checks before any material is read: the numbers of the extensions
// penumbra reads, alphaMode one of the spec's three, and each texture's
// KHR_texture_transform with offset and scale within the texture-coordinate limit.
#include "io/gltf_checks.h"

#include "io/float_checks.h"

#include <fmt/format.h>

#include <cmath>

namespace penumbra {

namespace {

// A number an extension object holds under `key`: absent = `fallback`; present and
// not a finite number = refused.
double extensionNumber(const tinygltf::ExtensionMap& ext, const char* name, const char* key, double fallback,
                       const std::string& where, const std::string& path) {
  auto it = ext.find(name);
  if (it == ext.end() || !it->second.IsObject() || !it->second.Has(key)) return fallback;
  const tinygltf::Value& v = it->second.Get(key);
  const double d = v.IsNumber() || v.IsInt() ? v.GetNumberAsDouble() : NAN;
  if (!std::isfinite(d)) gltfFail(path, where + ".extensions." + name + "." + key, "must be a finite number");
  return d;
}

// KHR_texture_transform's offset and scale multiply and shift the uvs, which are
// within kMaxTexCoord: bounded alike, uv x scale + offset stays a finite float (1e12
// at most). A rotation is an angle; any finite one is read (modulo 2 pi, in double).
void checkTextureTransform(const tinygltf::ExtensionMap& extensions, const std::string& where, const std::string& path) {
  auto it = extensions.find("KHR_texture_transform");
  if (it == extensions.end()) return;
  const std::string ext = where + ".extensions.KHR_texture_transform";
  if (!it->second.IsObject()) gltfFail(path, ext, "must be an object");
  for (const char* key : {"offset", "scale"}) {
    if (!it->second.Has(key)) continue;
    const tinygltf::Value& v = it->second.Get(key);
    const std::string at = ext + "." + key;
    if (!v.IsArray() || v.ArrayLen() != 2) gltfFail(path, at, "must be an array of 2 numbers");
    for (int i = 0; i < 2; ++i) {
      const tinygltf::Value& x = v.Get(i);
      if (!x.IsNumber() && !x.IsInt()) gltfFail(path, at, "must be an array of 2 numbers");
      const double d = x.GetNumberAsDouble();
      if (!(std::fabs(d) <= kMaxTexCoord)) {
        gltfFail(path, at, fmt::format("must be within +-{:g}, as texture coordinates are (a texture repeats every unit; "
                                       "beyond, its lookup loses all precision), got {:g}", kMaxTexCoord, d));
      }
    }
  }
  extensionNumber(extensions, "KHR_texture_transform", "rotation", 0.0, where, path);
}

}  // namespace

void checkGltfMaterial(const tinygltf::Material& g, const std::string& where, const std::string& path) {
  const double ior = extensionNumber(g.extensions, "KHR_materials_ior", "ior", 1.5, where, path);
  if (!(ior >= 1.0 && ior <= 100.0)) {
    gltfFail(path, where + ".extensions.KHR_materials_ior.ior", fmt::format("must be 1..100 (the spec's minimum is 1), got {:g}", ior));
  }
  const double strength = extensionNumber(g.extensions, "KHR_materials_emissive_strength", "emissiveStrength", 1.0, where, path);
  if (!(strength >= 0.0 && strength <= 1e30)) {
    gltfFail(path, where + ".extensions.KHR_materials_emissive_strength.emissiveStrength",
             fmt::format("must be 0..1e30, got {:g}", strength));
  }
  const double transmission = extensionNumber(g.extensions, "KHR_materials_transmission", "transmissionFactor", 0.0, where, path);
  if (!(transmission >= 0.0 && transmission <= 1.0)) {
    gltfFail(path, where + ".extensions.KHR_materials_transmission.transmissionFactor", "must be 0..1");
  }
  // tinygltf passes any string through; another would be read as OPAQUE.
  if (g.alphaMode != "OPAQUE" && g.alphaMode != "MASK" && g.alphaMode != "BLEND") {
    gltfFail(path, where + ".alphaMode", "must be \"OPAQUE\", \"MASK\" or \"BLEND\", got \"" + g.alphaMode + "\"");
  }
  const tinygltf::PbrMetallicRoughness& pbr = g.pbrMetallicRoughness;
  checkTextureTransform(pbr.baseColorTexture.extensions, where + ".pbrMetallicRoughness.baseColorTexture", path);
  checkTextureTransform(pbr.metallicRoughnessTexture.extensions, where + ".pbrMetallicRoughness.metallicRoughnessTexture", path);
  checkTextureTransform(g.normalTexture.extensions, where + ".normalTexture", path);
  checkTextureTransform(g.occlusionTexture.extensions, where + ".occlusionTexture", path);
  checkTextureTransform(g.emissiveTexture.extensions, where + ".emissiveTexture", path);
}

}  // namespace penumbra
