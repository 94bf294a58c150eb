// The list of glTF extensions penumbra reads, the hints for the common ones it does
// not (compressed geometry and textures), and the optional ones a file uses in vain.
#include "io/gltf_extensions.h"

#include <algorithm>

namespace penumbra {

namespace {

// Extensions the loader reads. A file may require any of them; one that requires
// another cannot be shown as its author meant, so it is refused.
const char* const kRead[] = {"KHR_lights_punctual",           "KHR_materials_emissive_strength",
                             "KHR_materials_ior",             "KHR_materials_transmission",
                             "KHR_materials_volume",          "KHR_texture_transform"};

struct Hint {
  const char* name;
  const char* why;
};

// What the file holds that penumbra cannot decode, and what it reads instead.
const Hint kHints[] = {
    {"KHR_draco_mesh_compression", "Draco-compressed meshes; penumbra reads uncompressed accessors"},
    {"EXT_meshopt_compression", "meshopt-compressed buffers; penumbra reads uncompressed buffers"},
    {"KHR_meshopt_compression", "meshopt-compressed buffers; penumbra reads uncompressed buffers"},
    {"KHR_texture_basisu", "KTX2 / Basis Universal textures; penumbra reads PNG and JPEG"},
    {"EXT_texture_webp", "WebP textures; penumbra reads PNG and JPEG"},
    {"EXT_texture_avif", "AVIF textures; penumbra reads PNG and JPEG"},
    {"KHR_mesh_quantization", "quantized vertex attributes; penumbra reads float positions"},
};

}  // namespace

bool readsGltfExtension(const std::string& name) {
  return std::any_of(std::begin(kRead), std::end(kRead), [&](const char* s) { return name == s; });
}

std::string supportedGltfExtensions() {
  std::string list;
  for (const char* s : kRead) list += (list.empty() ? "" : ", ") + std::string(s);
  return list;
}

std::string unsupportedExtensionHint(const std::string& name) {
  for (const Hint& h : kHints) {
    if (name == h.name) return h.why;
  }
  return "";
}

std::vector<std::string> ignoredGltfExtensions(const std::vector<std::string>& used) {
  std::vector<std::string> ignored;
  for (const std::string& name : used) {
    if (readsGltfExtension(name) || std::find(ignored.begin(), ignored.end(), name) != ignored.end()) continue;
    ignored.push_back(name);
  }
  return ignored;
}

}  // namespace penumbra
