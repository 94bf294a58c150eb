// The penumbra:* header attributes of a render's output image. Written once per
// image, so plain strings: readable with oiiotool --info -v or exrheader.
#include "plan/image_metadata.h"
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
  const bool gate = plan[Pass::Gate].on;
  const bool physical = scene.render.model == ShadingModel::Physical;
  std::string photons =
      physical ? fmt::format("global_photons={} caustic_photons={} k_global={} k_caustic={} "
                             "passes={} alpha={} radius={} max_bounces={} shadow_photons={} "
                             "k_shadow={} gate={}",
                             planBudgets(plan)[MapKind::Global], planBudgets(plan)[MapKind::Caustic], ps.kGlobal, ps.kCaustic, ps.passes,
                             ps.alpha, ps.radius, ps.maxBounces, stats.emitted[MapKind::Shadow], ps.kShadow,
                             onOff(gate))
               : fmt::format("shadow_photons={} indirect_photons={} k_shadow={} k_indirect={} "
                             "max_radius={} max_bounces={} sampling={} gate={} estimator={}",
                             stats.emitted[MapKind::Shadow], stats.emitted[MapKind::Indirect], ps.kShadow, ps.kIndirect,
                             ps.maxRadius, ps.maxBounces,
                             ps.sampling == HemisphereSampling::Cosine ? "cosine" : "uniform",
                             onOff(gate),
                             ps.estimator == IndirectEstimator::Classic ? "classic" : "density");
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
  const bool physical = rs.model == ShadingModel::Physical;
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
  add("packets", onOff(choices.packets));
  auto rgb = [](const Color& c) { return fmt::format("{} {} {}", c.r, c.g, c.b); };
  add("background", rgb(rs.background));
  if (!physical) add("ambient", rgb(rs.ambient));
  add("photons.shadow", budgets[MapKind::Shadow]);
  add("photons.k_shadow", ps.kShadow);
  if (physical) {
    add("photons.global", budgets[MapKind::Global]);
    add("photons.caustic", budgets[MapKind::Caustic]);
    add("photons.k_global", ps.kGlobal);
    add("photons.k_caustic", ps.kCaustic);
    add("photons.passes", ps.passes);
    add("photons.alpha", ps.alpha);
    add("photons.radius", ps.radius);
    if (stats.passes > 1) add("photons.final_global_radius", stats.globalRadius);
    if (stats.passes > 1) add("photons.final_caustic_radius", stats.causticRadius);
  } else {
    add("photons.indirect", budgets[MapKind::Indirect]);
    add("photons.k_indirect", ps.kIndirect);
    add("photons.max_radius", ps.maxRadius);
    add("photons.sampling", ps.sampling == HemisphereSampling::Cosine ? "cosine" : "uniform");
    add("photons.estimator", ps.estimator == IndirectEstimator::Classic ? "classic" : "density");
  }
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

ImageMetadata renderMetadata(const Scene& scene, const RenderPlan& plan, const RenderStats& stats,
                             const std::string& aov, const std::string& outputPath) {
  ImageMetadata m = {{"penumbra:scene", scene.name},
                     {"penumbra:scene_file", scene.file},
                     {"penumbra:aov", aov},
                     {"penumbra:model", scene.render.model == ShadingModel::Physical ? "physical" : "classic"},
                     {"penumbra:settings", summary(scene, plan, stats)}};
  if (isExr(outputPath)) addSettings(scene, plan, stats, m);
  return m;
}

}  // namespace penumbra
