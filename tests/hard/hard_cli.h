// What the hard cases that run the binary share: the command-line runner and a small
// classic scene (a floor quad under a point light, seen from above).
#pragma once
#include "support/cli_run.h"

namespace penumbra::hard {

using testing::CliResult;
using testing::quote;
using testing::runCli;
using testing::runShell;
using testing::ScratchDir;
namespace fs = std::filesystem;

inline constexpr const char* kFloorScene =
    R"({"camera": {"position": [0, 3, 3], "look_at": [0, 0, 0], "width": 16, "height": 12},
  "lights": [{"type": "point", "position": [0, 2, 0], "intensity": 5}],
  "objects": [{"type": "quad", "corner": [-1, 0, 1], "edge1": [2, 0, 0], "edge2": [0, 0, -2]}],
  "photons": {"shadow": 2000, "indirect": 2000}})";

// How many times `part` occurs in `text` (a note said once, a line per scene).
inline size_t occurrences(const std::string& text, const std::string& part) {
  size_t n = 0;
  for (size_t at = text.find(part); at != std::string::npos; at = text.find(part, at + 1)) ++n;
  return n;
}

}  // namespace penumbra::hard
