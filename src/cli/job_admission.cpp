// The order matters: output paths first (instant, and the commonest mistake), then
// memory without the photons, then the BVH (its size is already checked), then the
// photon estimate, measured by a pilot when the analytic bound is big enough to matter.
#include "cli/job_admission.h"
#include "cli/output_safety.h"
#include "cli/photon_pilot.h"
#include <fmt/format.h>

namespace penumbra {

Admission admitRender(const Scene& scene, const RenderRequest& request, Aov aov, int threads) {
  std::vector<OutputPath> outputs;
  const bool toStdout = request.outputPath.empty() || request.outputPath == "-";
  if (!request.outputPath.empty() && !(request.tracePixel && toStdout)) {
    outputs.push_back({request.outputPath, "-o", !request.tracePixel});
  }
  for (const std::string& stats : request.statsPaths) outputs.push_back({stats, "--stats", false});
  checkOutputs(outputs, sceneInputs(scene, request.scenePath));

  Admission a;
  a.options.aov = aov;
  a.options.threads = threads;
  a.options.tracePixel = request.tracePixel.has_value();
  a.bound = analyticStoreRates(scene);
  a.estimate = estimateResources(scene, a.options, a.bound);
  a.limit = memoryLimit(request.maxMemoryBytes);
  ResourceEstimate withoutPhotons = a.estimate;
  withoutPhotons.photonPeakBytes = withoutPhotons.cacheBytes = 0.0;
  checkMemory(withoutPhotons, a.limit, scene.file);
  return a;
}

void confirmRender(Admission& a, Scene& scene, const TraceScene& tracer, const RenderRequest& request) {
  if (a.estimate.photonPeakBytes > kPilotThresholdBytes) {
    a.estimate = estimateResources(scene, a.options,
                                   measureStoreRates(scene, tracer, a.estimate.plan, a.bound));
  }
  checkMemory(a.estimate, a.limit, scene.file);
  if (a.estimate.seconds() > kLongJobSeconds && request.notice) request.notice(longJobNote(a.estimate));
}

std::string longJobNote(const ResourceEstimate& e) {
  return fmt::format("estimated ~{} on {} thread{} (photons {}, render {}; memory {})",
                     formatDuration(e.seconds()), e.threads, e.threads == 1 ? "" : "s",
                     formatDuration(e.photonSeconds), formatDuration(e.renderSeconds),
                     formatBytes(e.totalBytes()));
}

}  // namespace penumbra
