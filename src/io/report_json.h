// JSON reports: the --stats file and the --trace-pixel ray tree.
#pragma once
#include "core/ray_record.h"
#include "core/stats.h"
#include <string>

namespace penumbra {

std::string statsToJson(const RenderStats& stats);
std::string rayTreeToJson(const RayTree& tree, int x, int y);

// The short human summary printed to stderr after a render.
std::string statsSummary(const RenderStats& stats);

}  // namespace penumbra
