// Serialises render statistics and ray trees with nlohmann::json.
#include "io/report_json.h"
#include "core/error.h"
#include <fmt/format.h>
#include <nlohmann/json.hpp>
#include <filesystem>
#include <fstream>
#include <unistd.h>

namespace penumbra {
namespace {
nlohmann::json vec(const Vec3& v) { return {v.x, v.y, v.z}; }
}  // namespace

std::string statsToJson(const RenderStats& s) {
  nlohmann::json j;
  j["scene"] = s.scene;
  j["image"] = {{"width", s.width}, {"height", s.height}, {"spp", s.spp}};
  j["threads"] = s.threads;
  j["seed"] = s.seed;
  j["time_s"] = {{"load", s.time.load},           {"build_bvh", s.time.buildBvh},
                 {"emit", s.time.emit},           {"build_maps", s.time.buildMaps},
                 {"precompute", s.time.precompute},
                 {"render", s.time.render},       {"write", s.time.write},
                 {"total", s.time.total}};
  const RayCounts& r = s.rays;
  j["rays"] = {{"camera", r.camera}, {"shadow", r.shadow}, {"reflection", r.reflection},
               {"refraction", r.refraction}};
  j["model"] = s.model;
  j["passes"] = s.passes;
  const ErrorEstimate& e = s.error;
  const char* source = e.source == ErrorSource::Passes    ? "passes"
                       : e.source == ErrorSource::Samples ? "samples"
                       : e.source == ErrorSource::Probes  ? "probes"
                                                          : "none";
  j["error"] = {{"noise_rmse", e.known() ? nlohmann::json(e.noiseRmse) : nlohmann::json(nullptr)},
                {"source", source}, {"count", e.count},
                {"bias_rmse", e.biasRmse >= 0.0 ? nlohmann::json(e.biasRmse) : nlohmann::json(nullptr)},
                {"bias_half", e.biasHalf}, {"bias_from_gathers", e.biasFromGathers}, {"lower_bound", e.lowerBound}, {"text", describeError(e)}};
  // The lighting: the pixels that see no emitter (core/error_estimate.h).
  auto known = [](double v) { return v >= 0.0 ? nlohmann::json(v) : nlohmann::json(nullptr); };
  j["error"]["lighting_noise_rmse"] = known(e.lightingNoiseRmse);
  j["error"]["lighting_bias_rmse"] = known(e.lightingBiasRmse);
  j["error"]["lighting_bias_bound"] = known(e.lightingBiasBound);
  j["error"]["emitter_share"] = e.emitterShare;
  j["error"]["bias_within_noise"] = e.biasWithinNoise;
  const PixelBounds& box = e.biasRegion;
  j["error"]["bias_region"] = nullptr;
  if (!box.empty()) {
    j["error"]["bias_region"] = {{"x0", box.x0}, {"x1", box.x1}, {"y0", box.y0}, {"y1", box.y1},
                                 {"share", e.biasRegionShare}, {"area", e.biasRegionArea}};
  }
  if (!s.budget.empty()) j["budget"] = {{"given", s.budget}, {"stopped", s.budgetStop}, {"passes", s.passes}};
  j["photons"] = {{"final_radius_caustic", s.gatherRadius[MapKind::Caustic]},
                  {"final_radius_global", s.gatherRadius[MapKind::Global]}};
  for (MapKind k : kAllMaps) {
    // The volume map exists only in scenes with a medium: the others' stats stay as they were.
    if (k == MapKind::Volume && s.emitted[k] == 0 && s.stored[k] == 0) continue;
    j["photons"][std::string("emitted_") + mapName(k)] = s.emitted[k];
    j["photons"][std::string("stored_") + mapName(k)] = s.stored[k];
  }
  j["gate"] = {{"mode", s.gateMode},             {"on", s.gate},
               {"reason", s.gateReason},
               {"queries", r.gateQueries},      {"lit", r.gateLit},
               {"shadowed", r.gateShadowed},    {"mixed", r.gateMixed},
               {"shadow_rays_cast", r.shadow},  {"shadow_rays_avoided", r.shadowRaysAvoided}};
  if (!s.plan.empty()) j["plan"] = nlohmann::json::parse(s.plan);
  j["gather"] = {{"queries", r.gatherQueries},
                 {"mean_neighbours", r.gatherQueries ? double(r.gatherNeighbours) / r.gatherQueries : 0.0}};
  j["lookup"] = {{"mode", s.lookup}, {"cells", s.cacheRecords}, {"split_lines", s.cacheSplits}, {"cell_size", s.cacheCell},
                 {"queries", r.cacheLookups}, {"fallbacks", r.cacheFallbacks},
                 {"lazy_cells", s.cacheLazyCells}};
  j["memory"] = {{"photon_maps_bytes", s.photonMapBytes}, {"lookup_cache_bytes", s.cacheBytes}};
  j["numeric"] = {{"nonfinite_samples", r.nonfiniteSamples}};
  j["peak_rss_bytes"] = s.peakRssBytes;
  // What loading left unread or added (a glTF scene; empty lists for a JSON one).
  j["load"] = {{"ignored_extensions", s.ignoredExtensions}, {"defaults_added", s.defaultsAdded}};
  return j.dump(2) + "\n";
}

std::string rayTreeToJson(const RayTree& tree, int x, int y) {
  nlohmann::json rays = nlohmann::json::array();
  for (size_t i = 0; i < tree.size(); ++i) {
    const RayRecord& r = tree[i];
    nlohmann::json n = {{"id", i}, {"kind", r.kind}, {"parent", r.parent}, {"depth", r.depth},
                        {"origin", vec(r.origin)}, {"direction", vec(r.dir)}, {"hit", r.hit},
                        {"weight", vec(r.weight)}, {"contribution", vec(r.contribution)}};
    if (r.hit) {
      n["t"] = r.t;
      n["position"] = vec(r.position);
      n["material"] = r.material;
      n["side"] = r.entering ? "front" : "back";
    }
    if (r.shaded) {
      if (r.hasUv) n["uv"] = {r.uv.x, r.uv.y};
      n["normal"] = {{"geometric", vec(r.geometricNormal)}, {"interpolated", vec(r.interpolatedNormal)},
                     {"shading", vec(r.shadingNormal)}, {"map_tilt_degrees", normalTiltDegrees(r)}};
      nlohmann::json mat = {{"base_color", vec(r.baseColor)}};
      if (r.metalRough) {
        mat["metallic"] = r.metallic;
        mat["roughness"] = r.roughness;
      }
      n["evaluated"] = std::move(mat);
    }
    if (!r.note.empty()) n["note"] = r.note;
    rays.push_back(std::move(n));
  }
  return nlohmann::json({{"pixel", {x, y}}, {"rays", rays}}).dump(2) + "\n";
}

std::string statsSummary(const RenderStats& s, bool detail) {
  const RayCounts& r = s.rays;
  std::string out = fmt::format(
      "{}: {}x{} spp {} on {} thread{} in {:.2f} s (load {:.2f}, bvh {:.2f}, photons {:.2f}+{:.2f}, "
      "{}render {:.2f})\n  rays: {} camera, {} shadow, {} reflection, {} refraction\n",
      s.scene, s.width, s.height, s.spp, s.threads, s.threads == 1 ? "" : "s", s.time.total,
      s.time.load, s.time.buildBvh, s.time.emit, s.time.buildMaps,
      s.cacheRecords ? fmt::format("precompute {:.2f}, ", s.time.precompute) : "", s.time.render,
      r.camera, r.shadow, r.reflection, r.refraction);
  if (s.error.known()) out += "  error: " + describeError(s.error) + "\n";
  if (!s.budget.empty()) {
    out += fmt::format("  budget {}: {} after {} passes (--set photons.passes={} renders the same image)\n", s.budget,
                       s.budgetStop, s.passes, s.passes);
  }
  if (r.nonfiniteSamples) {
    out += fmt::format("  warning: {} sample{} came out NaN or infinite and {} dropped (numeric.nonfinite_samples)\n",
                       r.nonfiniteSamples, r.nonfiniteSamples == 1 ? "" : "s",
                       r.nonfiniteSamples == 1 ? "was" : "were");
  }
  if (s.cacheRecords) {
    const std::string splits = s.cacheSplits ? fmt::format(" ({} strata answered by a split line)", s.cacheSplits) : "";
    out += fmt::format("  lookup: precomputed, {} cells of {:.4g}{}, {:.1f} MB; {} queries, {} with no cell near "
                       "(answered by {} cells computed on first use)\n",
                       s.cacheRecords, s.cacheCell, splits, s.cacheBytes / 1e6, r.cacheLookups, r.cacheFallbacks,
                       s.cacheLazyCells);
  }
  if (detail && s.gateMode == "auto") out += fmt::format("  gate: {}\n", s.gateReason);
  if (r.gateQueries) {
    out += fmt::format("  gate: {} queries, {:.1f}% lit, {:.1f}% shadowed, {:.1f}% mixed; {} shadow rays avoided\n",
                       r.gateQueries, 100.0 * r.gateLit / r.gateQueries,
                       100.0 * r.gateShadowed / r.gateQueries, 100.0 * r.gateMixed / r.gateQueries,
                       r.shadowRaysAvoided);
  }
  if (s.emitted[MapKind::Caustic] || s.emitted[MapKind::Global]) {
    out += fmt::format("  photons ({} pass{}): {} caustic stored of {} emitted, {} global stored of {} emitted\n",
                       s.passes, s.passes == 1 ? "" : "es", s.stored[MapKind::Caustic], s.emitted[MapKind::Caustic],
                       s.stored[MapKind::Global], s.emitted[MapKind::Global]);
  }
  if (s.emitted[MapKind::Shadow] || s.emitted[MapKind::Indirect]) {
    out += fmt::format("  photons: {} shadow stored of {} emitted, {} indirect stored of {} emitted, maps {:.1f} MB\n",
                       s.stored[MapKind::Shadow], s.emitted[MapKind::Shadow], s.stored[MapKind::Indirect], s.emitted[MapKind::Indirect],
                       s.photonMapBytes / 1e6);
  }
  return out;
}

}  // namespace penumbra
