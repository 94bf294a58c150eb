// The one-line refusal a scene text gets from the loader, for tests that assert on it.
#pragma once
#include "core/error.h"
#include "io/scene_loader.h"
#include <string>
#include <vector>

namespace penumbra::testing {

// The InputError message parseScene throws for `json` (as file "x.json"), or "" when it loads.
inline std::string errorOf(const std::string& json, const std::vector<std::string>& overrides = {}) {
  try {
    parseScene(json, "x.json", overrides);
  } catch (const InputError& e) {
    return e.what();
  }
  return "";
}

}  // namespace penumbra::testing
