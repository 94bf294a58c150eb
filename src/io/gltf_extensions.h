// The glTF extensions penumbra reads: a file that requires any other is refused by
// name, and the optional ones a file uses that penumbra leaves unread are listed for
// one note.
#pragma once
#include <string>
#include <vector>

namespace penumbra {

// True for an extension penumbra reads (or whose absence cannot change the image).
bool readsGltfExtension(const std::string& name);

// "KHR_lights_punctual, KHR_materials_emissive_strength, ...": for messages.
std::string supportedGltfExtensions();

// Why `name`, required by a file, cannot be read ("decompress the meshes first"); ""
// for an extension penumbra knows nothing about.
std::string unsupportedExtensionHint(const std::string& name);

// The names in `used` (a file's extensionsUsed) penumbra does not read, each once, in
// the file's order.
std::vector<std::string> ignoredGltfExtensions(const std::vector<std::string>& used);

}  // namespace penumbra
