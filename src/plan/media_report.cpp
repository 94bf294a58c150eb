// Media counters as JSON and as a summary line.
#include "plan/media_report.h"
#include <fmt/format.h>
#include <nlohmann/json.hpp>

namespace penumbra {
namespace {
double perGather(const RayCounts& r) { return r.volumeGathers ? double(r.volumeNeighbours) / r.volumeGathers : 0.0; }
}  // namespace

nlohmann::json mediaCountsJson(const RayCounts& r) {
  return {{"segments", r.mediumSegments},         {"samples", r.mediumSamples},
          {"volume_gathers", r.volumeGathers},     {"volume_neighbours", r.volumeNeighbours},
          {"volume_mean_neighbours", perGather(r)}, {"transmittance_rays", r.transmittanceRays}};
}

std::string mediaCountsLine(const RenderStats& s) {
  const RayCounts& r = s.rays;
  return fmt::format("  media: {} segments, {} samples, {} transmittance rays; volume map {} stored of {} emitted, "
                     "{} gathers ({:.1f} photons each)\n",
                     r.mediumSegments, r.mediumSamples, r.transmittanceRays, s.stored[MapKind::Volume],
                     s.emitted[MapKind::Volume], r.volumeGathers, perGather(r));
}

}  // namespace penumbra
