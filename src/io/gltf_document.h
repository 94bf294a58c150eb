// A glTF file's bytes before tinygltf parses them: its size, the GLB header, the
// JSON's nesting depth, and the checks that must come before parsing because
// tinygltf acts on them unchecked (asset version, required extensions, buffer and
// buffer view bounds, the external files it would read).
#pragma once
#include "io/gltf_files.h"
#include "io/load_limits.h"
#include <string>
#include <vector>

namespace penumbra {

struct GltfSource {
  std::vector<unsigned char> bytes;  // the whole file
  std::string json;                  // its JSON: the file, or a GLB's first chunk
  uint64_t binBytes = 0;             // a GLB's BIN chunk, 0 = none
  bool binary = false;
};

// Reads `path` (a regular file within limits) and splits a GLB into its chunks.
GltfSource readGltfSource(const std::string& path, const LoadLimits& limits);

// Checks the JSON before tinygltf sees it and allows in `files` every external
// buffer and image it names. `folder` is the model's (absolute).
void checkGltfDocument(const GltfSource& source, const std::string& path, const std::string& folder,
                       const LoadLimits& limits, GltfFiles& files);

}  // namespace penumbra
