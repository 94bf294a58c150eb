// Reads a JSON scene file into plain Scene data, validating every field.
#pragma once
#include "core/scene.h"
#include "io/load_limits.h"
#include <string>
#include <vector>

namespace penumbra {

// What loading may add to a file: decided once per command (--no-defaults).
class LoadCache;

struct LoadOptions {
  // A .gltf/.glb/.obj scene without a camera gets one framing it, without a light a
  // studio environment (io/scene_defaults.h); false keeps the file as it is.
  bool defaults = true;
  // Files earlier loads of this process read (io/load_cache.h); null: read them all.
  LoadCache* cache = nullptr;
  // --camera: "" the model's first camera (framed when it has none), "auto" framed
  // whatever the files place, else one of a glTF file's cameras by name or index
  // (io/gltf_cameras.h).
  std::string camera;
  // The command-line options above that change a picture (--no-defaults, --camera X):
  // what a saved output or frame was made with.
  std::vector<std::string> flags() const;
};

// Loads `path`, applying `overrides` ("render.max_depth=8", JSON-typed values)
// before validation. Throws InputError with a one-line message naming the file,
// the JSON path (objects[3].radius) and the problem. A file that would make loading
// allocate more than `limits` allows is refused before it is read whole.
Scene loadScene(const std::string& path, const std::vector<std::string>& overrides = {},
                const LoadLimits& limits = {}, const LoadOptions& options = {});

// Same, from JSON text; `fileName` is used for messages and to resolve relative paths.
Scene parseScene(const std::string& jsonText, const std::string& fileName,
                 const std::vector<std::string>& overrides = {}, const LoadLimits& limits = {});

}  // namespace penumbra
