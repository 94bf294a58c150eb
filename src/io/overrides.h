// --set overrides: "render.max_depth=8", "objects[2].radius=3" applied to the
// scene JSON before validation, so overridden values are checked like any other.
#pragma once
#include <nlohmann/json.hpp>
#include <string>
#include <vector>

namespace penumbra {

// Applies each override in order. VALUE is parsed as JSON, or taken as a plain
// string when it is not valid JSON. Missing intermediate objects are created;
// array indices must already exist. Throws InputError `--set "...": problem`.
// Returns the canonical JSON path each override wrote ("objects[2].radius").
std::vector<std::string> applyOverrides(nlohmann::json& document,
                                        const std::vector<std::string>& overrides);

}  // namespace penumbra
