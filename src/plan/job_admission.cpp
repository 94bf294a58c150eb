// The order matters: memory without the photons first (instant), then the BVH (its
// size is already checked), then the photon estimate, measured by a pilot when the
// analytic bound is big enough to matter. Output paths are checked before both.
#include "plan/job_admission.h"
#include "plan/photon_pilot.h"
#include "plan/photon_stage.h"
#include "plan/transport_model.h"
#include <fmt/format.h>

namespace penumbra {

PhotonPlan photonPlanOf(const RenderPlan& plan, const Scene& scene, bool tracePixel) {
  const MapCounts b = planBudgets(plan);
  const TransportModel& model = transportOf(scene);
  const int passes = tracePixel ? 1 : model.passes(scene, plan.aov);
  return {b, passes, model.freshPhotonsEachPass() ? passes : 1};
}

Admission admitJob(const Scene& scene, const RenderPlan& plan, int threads, bool tracePixel,
                   uint64_t maxMemoryBytes) {
  Admission a;
  a.options.photons = photonPlanOf(plan, scene, tracePixel);
  a.options.aov = plan.aov;
  a.options.threads = threads;
  a.options.tracePixel = tracePixel;
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
  if (a.estimate.seconds() > kLongJobSeconds && notice) notice(longJobNote(a.estimate));
}

std::string longJobNote(const ResourceEstimate& e) {
  return fmt::format("estimated ~{} on {} thread{} (photons {}, render {}; memory {})",
                     formatDuration(e.seconds()), e.threads, e.threads == 1 ? "" : "s",
                     formatDuration(e.photonSeconds), formatDuration(e.renderSeconds),
                     formatBytes(e.totalBytes()));
}

}  // namespace penumbra
