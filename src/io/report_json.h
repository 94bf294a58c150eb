// JSON reports: the --stats file and the --trace-pixel ray tree.
#pragma once
#include "core/ray_record.h"
#include "core/stats.h"
#include <string>

namespace penumbra {

std::string statsToJson(const RenderStats& stats);
std::string rayTreeToJson(const RayTree& tree, int x, int y);

// The short human summary printed to stderr after a render; `detail` (-v or --stats)
// adds the reason of an automatic gate decision, which most renders need not read.
std::string statsSummary(const RenderStats& stats, bool detail = false);

}  // namespace penumbra
