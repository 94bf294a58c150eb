// The order matters: memory without the photons first (instant), then the BVH (its
// size is already checked), then the photon estimate, measured by a pilot when the
// analytic bound is big enough to matter. Output paths are checked before both.
#include "plan/job_admission.h"
#include "plan/photon_pilot.h"
#include "plan/photon_stage.h"
#include "plan/transport_model.h"
#include "core/lights/environment_map.h"
#include <fmt/format.h>
#include <algorithm>
#include <cmath>

namespace penumbra {

namespace {

// Per pass, the physical maps' photons the environment starts (the volume map's
// too, in a scene with a medium): its share of each split, or the whole budget when
// it is the only light.
uint64_t environmentPhotons(const RenderPlan& plan, const Scene& scene) {
  const Light* sky = environmentOf(scene);
  if (!sky) return 0;
  uint64_t n = 0;
  for (Pass pass : {Pass::GlobalPhotons, Pass::CausticPhotons, Pass::VolumePhotons}) {
    const PassDecision& d = plan[pass];
    if (!d.on) continue;
    if (d.perLight.size() == scene.lights.size()) {
      for (size_t l = 0; l < scene.lights.size(); ++l) n += &scene.lights[l] == sky ? d.perLight[l] : 0;
    } else if (scene.lights.size() == 1) {
      n += d.budget;
    }
  }
  return n;
}

}  // namespace

PhotonPlan photonPlanOf(const RenderPlan& plan, const Scene& scene, bool tracePixel) {
  const MapCounts b = planBudgets(plan);
  const TransportModel& model = transportOf(scene);
  const int passes = tracePixel ? 1 : model.passes(scene, plan.aov);
  return {b, passes, model.freshPhotonsEachPass() ? passes : 1, environmentPhotons(plan, scene)};
}

Admission admitJob(const Scene& scene, const RenderPlan& plan, int threads, bool tracePixel,
                   uint64_t maxMemoryBytes, const RenderBudget& budget) {
  Admission a;
  if (!tracePixel && readsLight(plan.aov)) a.budget = budget;  // only views of light run passes
  a.options.photons = photonPlanOf(plan, scene, tracePixel);
  a.options.aov = plan.aov;
  a.options.threads = threads;
  a.options.tracePixel = tracePixel;
  a.options.budgeted = a.budget.any();
  const FrameChoices choices = choicesOf(plan, scene);
  a.options.shadows = choices.shadows;
  a.options.lightSamples = choices.lightSamples;
  a.options.precomputed = precomputedLookups(plan);
  a.bound = analyticStoreRates(scene);
  a.estimate = estimateResources(scene, a.options, a.bound);
  a.limit = memoryLimit(maxMemoryBytes);
  ResourceEstimate withoutPhotons = a.estimate;
  withoutPhotons.photonPeakBytes = withoutPhotons.cacheBytes = 0.0;
  checkMemory(withoutPhotons, a.limit, scene.file);
  return a;
}

void confirmJob(Admission& a, const Scene& scene, const TraceScene& tracer,
                const std::function<void(const std::string&)>& notice) {
  if (a.estimate.photonPeakBytes > kPilotThresholdBytes) {
    a.estimate = estimateResources(scene, a.options, measureStoreRates(scene, tracer, a.estimate.plan, a.bound));
  }
  checkMemory(a.estimate, a.limit, scene.file);
  a.budgetSeconds = budgetBoundSeconds(a.budget, a.estimate);
  const double seconds = a.budget.any() ? a.budgetSeconds : a.estimate.seconds();
  if (seconds > kLongJobSeconds && notice) notice(longJobNote(a));
}

namespace {
// One progressive pass as the estimate prices it: the whole render less the BVH build.
double secondsPerPass(const ResourceEstimate& e) {
  return (e.seconds() - e.bvhSeconds) / std::max(e.plan.passes, 1);
}
}  // namespace

double budgetBoundSeconds(const RenderBudget& b, const ResourceEstimate& e) {
  if (!b.any()) return 0.0;
  const double pass = secondsPerPass(e);
  double bound = e.bvhSeconds + kBudgetMaxPasses * pass;
  if (b.seconds > 0.0) bound = std::min(bound, std::max(b.seconds * (1.0 + kTimeLimitOverrun), e.bvhSeconds + 2.0 * pass));
  return bound;
}

std::string longJobNote(const Admission& a) {
  const ResourceEstimate& e = a.estimate;
  const std::string threads = fmt::format("{} thread{}", e.threads, e.threads == 1 ? "" : "s");
  if (a.budget.any()) {
    const double pass = secondsPerPass(e);
    const double passes = std::min<double>(kBudgetMaxPasses, std::max(2.0, std::floor((a.budgetSeconds - e.bvhSeconds) / pass)));
    return fmt::format("{} may run up to ~{} on {} (~{:.0f} passes of ~{} each; memory {})", describeBudget(a.budget),
                       formatDuration(a.budgetSeconds), threads, passes, formatDuration(pass), formatBytes(e.totalBytes()));
  }
  return fmt::format("estimated ~{} on {} (photons {}, render {}; memory {})", formatDuration(e.seconds()), threads,
                     formatDuration(e.photonSeconds), formatDuration(e.renderSeconds), formatBytes(e.totalBytes()));
}

}  // namespace penumbra
