// A sweep knob that changed nothing: every group of runs that differ only in that
// knob rendered identical images. Said after the sweep, with the likely reason.
#pragma once
#include "plan/sweep/sweep_results.h"
#include "plan/sweep/sweep_spec.h"
#include <filesystem>
#include <string>
#include <vector>

namespace penumbra {

// One note per idle knob; `dir` is the sweep folder the rows' images are under.
std::vector<std::string> idleKnobNotes(const SweepSpec& spec, const std::vector<SweepRow>& rows,
                                       const std::filesystem::path& dir);

}  // namespace penumbra
