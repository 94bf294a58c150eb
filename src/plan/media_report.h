// The media counters in a render's reports (--stats "media", the summary's media
// line), written only for a scene with a medium so every other report stays as it was.
#pragma once
#include "core/stats.h"
#include <nlohmann/json_fwd.hpp>
#include <string>

namespace penumbra {

// {"segments", "samples", "volume_gathers", "volume_mean_neighbours", "transmittance_rays"}.
nlohmann::json mediaCountsJson(const RayCounts& r);

// "  media: 1200 segments, 4800 samples, 2400 transmittance rays; volume map 9000 stored
// of 200000 emitted, 1200 gathers (87.5 photons each)"
std::string mediaCountsLine(const RenderStats& s);

}  // namespace penumbra
