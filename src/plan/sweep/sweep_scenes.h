// penumbra sweep over several scenes: each into a folder of its own name under the
// output, and scenes.md, one line per scene with its best and fastest runs.
#pragma once
#include "plan/sweep/sweep_results.h"
#include "plan/sweep/sweep_run.h"
#include <string>
#include <vector>

namespace penumbra {

// One scene: `out` itself; several: out/<file name without extension> each.
// Throws InputError when two scenes would share a folder.
std::vector<std::string> sceneFolders(const std::vector<std::string>& scenes, const std::string& out);

struct SceneSweep {
  std::string scene;   // as given
  std::string folder;  // its results.csv and report.md
  SweepOutcome outcome;
};

// scenes.md: per scene its runs, the best run under `metric`, the fastest, and its report.
std::string scenesMarkdown(const std::vector<SceneSweep>& sweeps, SweepMetric metric);

}  // namespace penumbra
