// The penumbra:* header attributes of a render's output image. Written once per
// image, so plain strings: readable with oiiotool --info -v or exrheader.
#include "plan/image_metadata.h"
#include "plan/transport_model.h"
#include "plan/photon_stage.h"
#include <fmt/format.h>
#include <algorithm>
#include <cctype>
#include <filesystem>

#ifndef PENUMBRA_VERSION
#define PENUMBRA_VERSION "unknown"
#endif

namespace penumbra {
namespace {

const char* onOff(bool on) { return on ? "on" : "off"; }

// The one-line summary every output carries (unchanged since before the EXR keys).
std::string summary(const Scene& scene, const RenderPlan& plan, const RenderStats& stats) {
  const auto& ps = scene.photons;
  std::string photons = transportOf(scene).photonSummary(scene, planBudgets(plan), stats, plan[Pass::Gate].on);
  photons += precomputedLookups(plan)
                 ? fmt::format(" lookup=precomputed lookup_cell={}", ps.lookupCell)
                 : std::string(" lookup=exact");
  return fmt::format("{}x{} spp={} max_depth={} seed={} {}", scene.camera.width, scene.camera.height,
                     scene.camera.spp, scene.render.maxDepth, scene.render.seed, photons);
}

// One key per setting. Photon counts are per pass, as the plan budgeted them (0 =
// that map was not built); the model's unused settings are left out.
void addSettings(const Scene& scene, const RenderPlan& plan, const RenderStats& stats, ImageMetadata& m) {
  const RenderSettings& rs = scene.render;
  const PhotonSettings& ps = scene.photons;
  const FrameChoices choices = choicesOf(plan, scene);
  const MapCounts budgets = planBudgets(plan);
  const bool precomputed = precomputedLookups(plan);
  auto add = [&m](const std::string& key, const auto& value) { m.emplace_back("penumbra:" + key, fmt::format("{}", value)); };
  add("version", PENUMBRA_VERSION);
  add("width", scene.camera.width);
  add("height", scene.camera.height);
  add("spp", scene.camera.spp);
  add("seed", rs.seed);
  add("max_depth", rs.maxDepth);
  add("min_weight", rs.minWeight);
  add("shadows", onOff(choices.shadows));
  add("reflection", onOff(choices.reflection));
  add("refraction", onOff(choices.refraction));
  add("light_samples", choices.lightSamples);
  if (!scene.media.empty()) add("volume_samples", choices.volumeSamples);
  add("packets", onOff(choices.packets));
  auto rgb = [](const Color& c) { return fmt::format("{} {} {}", c.r, c.g, c.b); };
  add("background", rgb(rs.background));
  if (rs.transparentBackground) add("transparent_background", "on");  // absent: off, the header as before
  add("photons.shadow", budgets[MapKind::Shadow]);
  add("photons.k_shadow", ps.kShadow);
  transportOf(scene).addModelSettings(scene, budgets, stats, m);
  add("photons.max_bounces", ps.maxBounces);
  add("photons.lookup", precomputed ? "precomputed" : "exact");
  if (precomputed) add("photons.lookup_cell", ps.lookupCell);
  add("photons.gate", stats.gateMode);
  add("photons.gate_decision", onOff(choices.gate));
  if (!stats.plan.empty()) add("plan", stats.plan);
}

bool isExr(const std::string& path) {
  std::string ext = std::filesystem::path(path).extension().string();
  std::transform(ext.begin(), ext.end(), ext.begin(), [](unsigned char c) { return std::tolower(c); });
  return ext == ".exr";
}

}  // namespace

ImageMetadata errorMetadata(const ErrorEstimate& error) {
  ImageMetadata m = {{"penumbra:error", describeError(error)}};
  if (error.known()) m.emplace_back("penumbra:error.noise_rmse", fmt::format("{}", error.noiseRmse));
  // noise_rmse is then a lower bound (probes that found no error), not an estimate.
  if (error.lowerBound) m.emplace_back("penumbra:error.lower_bound", "1");
  if (error.biasRmse >= 0.0) m.emplace_back("penumbra:error.bias_rmse", fmt::format("{}", error.biasRmse));
  // The lighting's figures (pixels that see no emitter), and where the bias sits as
  // "x0,x1,y0,y1" (half-open, as --pixel-bounds takes it) with its share there.
  if (error.lightingKnown()) {
    m.emplace_back("penumbra:error.lighting_noise_rmse", fmt::format("{}", error.lightingNoiseRmse));
    m.emplace_back("penumbra:error.emitter_share", fmt::format("{}", error.emitterShare));
  }
  if (error.lightingBiasRmse >= 0.0) {
    m.emplace_back("penumbra:error.lighting_bias_rmse", fmt::format("{}", error.lightingBiasRmse));
  }
  if (error.lightingBiasBound >= 0.0) {
    m.emplace_back("penumbra:error.lighting_bias_bound", fmt::format("{}", error.lightingBiasBound));
  }
  const PixelBounds& r = error.biasRegion;
  if (!r.empty()) {
    m.emplace_back("penumbra:error.bias_region", fmt::format("{},{},{},{}", r.x0, r.x1, r.y0, r.y1));
    m.emplace_back("penumbra:error.bias_region_share", fmt::format("{}", error.biasRegionShare));
  }
  return m;
}

ImageMetadata renderMetadata(const Scene& scene, const RenderPlan& plan, const RenderStats& stats,
                             const std::string& aov, const std::string& outputPath) {
  ImageMetadata m = {{"penumbra:scene", scene.name},
                     {"penumbra:scene_file", scene.file},
                     {"penumbra:aov", aov},
                     {"penumbra:model", transportOf(scene).name()},
                     {"penumbra:settings", summary(scene, plan, stats)}};
  for (auto& kv : errorMetadata(stats.error)) m.push_back(std::move(kv));
  if (!stats.budget.empty())
    m.emplace_back("penumbra:budget", fmt::format("{}: {} after {} passes", stats.budget, stats.budgetStop, stats.passes));
  if (isExr(outputPath)) addSettings(scene, plan, stats, m);
  return m;
}

}  // namespace penumbra
