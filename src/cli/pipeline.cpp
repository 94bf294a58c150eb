// One render from scene file to image: load, admit, build the BVH, emit photons,
// build the maps (cli/photon_stage.h), render the frame (cli/render_frame.h), write.
#include "cli/pipeline.h"
#include "cli/gate_decision.h"
#include "cli/image_metadata.h"
#include "cli/job_admission.h"
#include "cli/render_frame.h"
#include "cli/render_plan.h"
#include "core/error.h"
#include "io/image_io.h"
#include "io/scene_loader.h"
#include "integrator/render.h"
#include <tbb/global_control.h>
#include <tbb/info.h>
#include <fmt/format.h>

namespace penumbra {
namespace {

void reportProgress(const RenderRequest& request, const char* phase, double fraction) {
  if (request.progress) request.progress(phase, fraction);
}

}  // namespace

RenderResult runRender(const RenderRequest& request) {
  Stopwatch total;
  int threads = request.threads > 0 ? request.threads : tbb::info::default_concurrency();
  tbb::global_control limit(tbb::global_control::max_allowed_parallelism, threads);
  RenderResult result;
  RenderStats& stats = result.stats;

  Stopwatch phase;
  Scene scene = loadScene(request.scenePath, request.overrides);
  stats.time.load = phase.seconds();
  const std::string aovName = request.aov.empty() ? scene.render.aov : request.aov;
  Aov aov = parseAov(aovName);
  const bool physical = scene.render.model == ShadingModel::Physical;
  if (!physical && (aov == Aov::Direct || aov == Aov::Caustic)) {
    throw InputError(scene.file + ": view '" + aovName +
                     "' needs the physical model (render.model: \"physical\")");
  }
  // Before any work: what runs and why (photons.gate = auto is decided here too).
  const GateMode gateMode = scene.photons.gateMode;
  stats.gateMode = gateMode == GateMode::Auto ? "auto" : gateMode == GateMode::On ? "on" : "off";
  RenderPlan plan = makePlan(scene, aov, request.plan);
  applyPlan(plan, scene);
  stats.gate = scene.photons.gate;
  stats.gateReason = plan[Pass::Gate].reason;
  for (const PassDecision& d : plan.passes) {
    if (d.overridden && d.changesImage) result.notes.push_back("plan override: " + d.reason);
  }
  // Bad pixels, outputs and oversized jobs fail now, not after minutes of photons and tiles.
  if (request.tracePixel) checkPixel(scene.camera, request.tracePixel->first, request.tracePixel->second);
  Admission admission = admitRender(scene, request, aov, threads);

  SceneAssets assets = prepareAssets(scene, plan[Pass::Textures].on);
  stats.time.buildBvh = assets.bvhSeconds;
  splitByReach(plan, scene, *assets.tracer);  // needs rays: the BVH is the first work
  applyPlan(plan, scene);
  stats.plan = planJson(plan);
  confirmRender(admission, scene, *assets.tracer, request);
  result.estimate = admission.estimate;

  stats.scene = scene.name;
  stats.width = scene.camera.width;
  stats.height = scene.camera.height;
  stats.spp = scene.camera.spp;
  stats.threads = threads;
  stats.seed = scene.render.seed;
  stats.model = physical ? "physical" : "classic";
  stats.lookup = scene.photons.lookup == PhotonLookup::Precomputed ? "precomputed" : "exact";

  reportProgress(request, "photons", 0.0);
  const PhotonNeeds needs = photonNeeds(plan);
  Emission emission = emitPhotonsFor(scene, *assets.tracer, needs, 0, {}, beginPhase(request.meter, "photons"));
  reportProgress(request, "maps", 0.0);
  PhotonStage stage;
  buildStage(emission, emission.budgets, true, stage, beginPhase(request.meter, "maps"));
  endPhase(request.meter);
  FrameOptions frame;
  frame.aov = aov;
  frame.needs = needs;
  frame.tracePixel = request.tracePixel;
  frame.progress = request.progress;
  frame.meter = request.meter;
  renderFrame(scene, assets, stage, frame, result);
  endPhase(request.meter);

  if (!request.outputPath.empty() && !request.tracePixel) {
    phase = Stopwatch();
    writeImage(request.outputPath, result.image, renderMetadata(scene, stats, aovName, request.outputPath),
               request.display);
    stats.time.write = phase.seconds();
  }
  stats.time.total = total.seconds();
  stats.peakRssBytes = peakRssBytes();
  return result;
}

}  // namespace penumbra
