// Reads a JSON scene file into plain Scene data, validating every field.
#pragma once
#include "core/scene.h"
#include "io/load_limits.h"
#include <string>
#include <vector>

namespace penumbra {

// Loads `path`, applying `overrides` ("render.max_depth=8", JSON-typed values)
// before validation. Throws InputError with a one-line message naming the file,
// the JSON path (objects[3].radius) and the problem. A file that would make loading
// allocate more than `limits` allows is refused before it is read whole.
Scene loadScene(const std::string& path, const std::vector<std::string>& overrides = {},
                const LoadLimits& limits = {});

// Same, from JSON text; `fileName` is used for messages and to resolve relative paths.
Scene parseScene(const std::string& jsonText, const std::string& fileName,
                 const std::vector<std::string>& overrides = {}, const LoadLimits& limits = {});

}  // namespace penumbra
