// One render, top to bottom: plan the job (load, view, outputs, passes, estimate),
// prepare it (BVH, light split, pilot), build its photon maps, render its frame with
// every pass, write the image. Every step is the render session's (render_session.h).
#include "plan/pipeline.h"
#include "plan/cpu_report.h"
#include "plan/frame_part.h"
#include "plan/image_metadata.h"
#include "plan/render_session.h"
#include "plan/saved_passes.h"
#include "io/image_io.h"
#include "core/error.h"
#include <filesystem>

namespace penumbra {

namespace {

// A render command's frame stamp: what changes its pixels besides the scene file.
std::string renderStamp(const PlannedJob& job, const SessionOptions& session) {
  std::vector<std::string> options;
  for (Pass p : session.plan.enable) options.push_back(std::string("--enable ") + passName(p));
  for (Pass p : session.plan.disable) options.push_back(std::string("--disable ") + passName(p));
  for (const std::string& f : session.load.flags()) options.push_back(f);
  return renderFrameStamp(job.request.scenePath, job.request.overrides, options, job.viewName);
}

}  // namespace

RenderResult runRender(const RenderRequest& request) {
  const CpuSpan total;
  RenderSession session(request.session);

  // Bad views, pixels, outputs and oversized jobs fail here, before any heavy work.
  JobRequest job;
  job.scenePath = request.scenePath;
  job.overrides = request.overrides;
  job.view = request.aov;
  job.tracePixel = request.tracePixel;
  job.budget = request.session.budget;
  job.tile = request.tile;
  if (request.tile && !request.outputPath.empty() && !request.tracePixel &&
      std::filesystem::path(request.outputPath).extension() != ".exr") {
    throw InputError("--tile/--pixel-bounds: a part of a frame is written as .exr (float, for penumbra merge): got -o " +
                     request.outputPath);
  }
  const bool toStdout = request.outputPath.empty() || request.outputPath == "-";
  if (!request.outputPath.empty() && !(request.tracePixel && toStdout)) {
    job.outputs.push_back({request.outputPath, "-o", !request.tracePixel});
  }
  for (const std::string& stats : request.statsPaths) job.outputs.push_back({stats, "--stats", false});
  const bool image = !request.outputPath.empty() && !request.tracePixel;
  if (image) job.savedPasses = savedPassesPath(request.outputPath);
  PlannedJob planned = session.plan(job);

  session.prepare(planned);
  PhotonStage& stage = session.photons(planned);
  RenderResult result = session.frame(planned, stage, request.jobClock);
  if (session.mapLoads() > 0) result.notes.push_back("photon maps: loaded from --map-dir " + request.session.mapDir);
  if (session.mapWrites() > 0) result.notes.push_back("photon maps: written to --map-dir " + request.session.mapDir);
  RenderStats& stats = result.stats;
  stats.time.buildBvh = session.geometry(planned).bvhSeconds;

  if (image) {
    Stopwatch phase;
    if (planned.bounds) {
      writeFramePart(request.outputPath, result, *planned.bounds, renderStamp(planned, request.session),
                     renderMetadata(planned.scene, planned.plan, stats, planned.viewName, "frame.exr"),
                     renderMetadata(planned.scene, planned.plan, stats, planned.viewName, "frame.png"));
    } else {
      writeImage(request.outputPath, result.image,
                 renderMetadata(planned.scene, planned.plan, stats, planned.viewName, request.outputPath),
                 sceneDisplay(request.display, planned.scene));
    }
    removeSavedPasses(job.savedPasses);  // the job is done: nothing to resume
    stats.time.write = phase.seconds();
  }
  stats.cpu = total.timing(stats.threads);
  stats.time.total = stats.cpu.wallSeconds;
  stats.peakRssBytes = peakRssBytes();
  const std::string contended = contendedNote({stats.cpu}, "render");
  if (!contended.empty()) result.notes.push_back(contended);
  return result;
}

}  // namespace penumbra
