// One frame from built photon maps: the context the integrators read, the
// precomputed lookups, and the physical model's progressive passes.
#include "plan/render_frame.h"
#include "plan/frame_run.h"
#include "plan/frame_lookups.h"
#include "plan/saved_passes.h"
#include "plan/transport_model.h"
#include "gather/lookup_cache/lookup_cache.h"
#include "gather/radiance_estimate.h"
#include "gather/volume_map.h"
#include "trace/camera.h"
#include "trace/emitter_mask.h"
#include "trace/light_visibility.h"
#include "trace/probe_error.h"
#include "trace/shading.h"
#include "core/adaptive_sampling.h"
#include "core/error.h"
#include "core/error_estimate.h"
#include "io/temp_file.h"
#include <fmt/format.h>
#include <optional>

namespace penumbra {
namespace {

void addStage(const PhotonStage& s, RenderStats& stats) {
  stats.time.emit += s.emitSeconds;
  stats.time.buildMaps += s.buildSeconds;
  stats.emitted += s.emitted;
  s.maps.forEach([&stats](MapKind k, const auto& map) { stats.stored[k] += map.size(); });
}

// The stats keep each light map's typical gather radius in the last pass: its fixed
// radius, or the median k-nearest one.
void gatherRadii(const TransportModel& model, const PhotonStage& maps, const ShadingContext& ctx,
                 RenderStats& stats) {
  GatherScratch scratch;
  for (MapKind k : model.lightMaps()) {
    const PhotonGather& g = ctx.gathers[k];
    if (k == MapKind::Volume) {
      // Its beam's radius (the map's rule from k); a scene without a medium builds no
      // volume map and keeps its stats as they were.
      const VolumePhotonMap& volume = maps.maps.get<MapKind::Volume>();
      if (!volume.empty()) stats.gatherRadius[k] = g.maxRadius > 0.0f ? g.maxRadius : volume.radiusFor(g.k);
      continue;
    }
    stats.gatherRadius[k] = g.k == 0 ? g.maxRadius : typicalKnnRadius(*maps.maps.light(k), g.k, scratch);
  }
}

// "render", or "render 2/4" in pass 2 of 4 progressive passes.
std::string phaseName(const char* phase, int pass, int passes) {
  return passes > 1 ? fmt::format("{} {}/{}", phase, pass + 1, passes) : std::string(phase);
}


// Adaptive sampling: from the passes so far, the pixels whose error is high take more
// samples in pass `pass`; the spp view counts every pixel's.
void planSamples(FrameRun& f, int pass) {
  f.render.extra = nullptr;
  if (f.adaptive && pass >= kAdaptiveFirstPass) {
    const ErrorEstimate e = f.spread.estimate();
    adaptiveExtras(f.spread.standardError(), e.lightingKnown() ? e.lightingNoiseRmse : e.noiseRmse, f.rule, f.extra);
    f.render.extra = &f.extra;
  }
  for (size_t i = 0; i < f.samples.size(); ++i) {
    f.samples[i] += uint32_t(f.scene.camera.spp) + (f.render.extra ? f.extra[i] : 0u);
  }
}

// The spp view: each pixel's camera samples, in every channel.
Image sampleCounts(const FrameRun& f) {
  Image out(f.scene.camera.width, f.scene.camera.height);
  for (size_t i = 0; i < f.samples.size(); ++i) out.pixels[i] = Color(float(f.samples[i]));
  return out;
}

// The maps pass `pass` reads: pass 0's, or a later physical pass's own fresh photons.
const PhotonStage& mapsForPass(FrameRun& f, int pass) {
  if (pass == 0 || !f.fresh) return f.stage;
  f.later = PhotonStage();
  PhotonNeeds needs = f.options.needs;
  needs.maps[MapKind::Shadow] = false;  // the gate's photons are pass 0's, for every pass
  const std::string name = f.budgeted ? fmt::format("pass {}", pass + 1) : phaseName("photons", pass, f.passes);
  Emission e = emitPhotonsFor(f.scene, *f.assets.tracer, needs, f.options.budgets, static_cast<uint32_t>(pass), {},
                              beginPhase(f.options.progress, name));
  buildStage(e, e.budgets, true, f.later, beginPhase(f.options.progress, phaseName("maps", pass, f.passes)));
  endPhase(f.options.progress);
  return f.later;
}

// The context reads `maps` in pass `pass`, with the pass's gathers.
void bindMaps(FrameRun& f, const PhotonStage& maps, int pass) {
  if (pass == 0 || f.fresh) addStage(maps, f.stats);
  maps.maps.forEach([&f](auto k, const auto& map) {
    if constexpr (decltype(k)::value != MapKind::Shadow) f.ctx.maps.get<decltype(k)::value>() = map.empty() ? nullptr : &map;
  });
  f.ctx.pass = static_cast<uint32_t>(pass);
  f.ctx.gathers = f.model.gathers(f.scene.photons, f.ctx.pass, static_cast<uint32_t>(f.passes));
  if (f.passes > 1 && f.fresh) gatherRadii(f.model, maps, f.ctx, f.stats);
}

// Pass 0 keeps its lookups with its maps, for later frames on the same maps; a pass
// on pass 0's maps reads pass 0's lookups. A gate with no precomputed verdicts votes
// over the shadow map's KD-trees, which the photon stage leaves out until a frame reads them.
void prepareLookups(FrameRun& f, int pass) {
  ShadingContext& ctx = f.ctx;
  PhotonStage& stage = f.stage;
  if (f.needsLight && f.precomputed && (f.fresh || pass == f.first)) {
    const std::string lookups = phaseName("lookups", pass, f.passes);
    if (pass == 0 || !f.fresh) {
      buildLookup(f.scene, f.model, stage.lookup, stage.gateLookup, &stage.lookupKey, &stage.gateLookupKey,
                  &stage.lookupSeconds, ctx, f.stats, f.options.progress, lookups);
    } else {
      // The gate's photons are pass 0's for every pass: so are its own cells.
      buildLookup(f.scene, f.model, f.cache, stage.gateLookup, nullptr, &stage.gateLookupKey, nullptr, ctx, f.stats,
                  f.options.progress, lookups);
    }
  }
  if (pass == f.first && f.needsLight && ctx.choices.gate && ctx.maps.get<MapKind::Shadow>() && !(ctx.gateLookup && ctx.gateLookup->hasGate()) &&
      !stage.maps.get<MapKind::Shadow>().hasTrees()) {
    Stopwatch trees;
    stage.maps.get<MapKind::Shadow>().buildTrees();
    f.stats.time.buildMaps += trees.seconds();
  }
}

// The pixels that see an emitter, for a frame whose error figure has a spread (passes
// or samples); its rays count as render time, as the probes' do.
// A frame without a spread finds them only when asked (the sweep's lighting error),
// off its render time: a lone render of it would not trace them.
void findEmitters(FrameRun& f) {
  const bool spread = f.passes >= 2 || f.render.standardError;
  if (!f.needsLight || (!spread && !f.options.findEmitters)) return;
  Stopwatch tracing;
  f.emitters = emitterMask(f.ctx, f.options.bounds ? &*f.options.bounds : nullptr);
  f.spread.setEmitterMask(f.emitters);
  (spread ? f.stats.time.render : f.result.emitterSeconds) += tracing.seconds();
}

// Whether this pass's gathers probe their smoothing bias for the bias figure: where
// the model probes it and no cached irradiance answers the global gathers unprobed
// (then the drift check measures it). Decided at the run's first pass, for all of them.
bool probesSmoothing(FrameRun& f) {
  if (f.done == f.first) f.probing = f.probing && !(f.ctx.lookup && f.ctx.lookup->indirectKind() == CachedIndirect::Irradiance);
  const bool probe = f.probing;
  for (MapKind k : f.model.lightMaps()) f.ctx.gathers[k].probeSmoothing = probe;
  f.render.smoothing = probe ? &f.smoothing : nullptr;
  return probe;
}

// Renders pass `pass` and adds it to the frame's sum and spread.
void renderPass(FrameRun& f, int pass) {
  Stopwatch phase;
  planSamples(f, pass);
  const bool probe = probesSmoothing(f);
  f.render.tiles = beginPhase(f.options.progress, f.budgeted ? fmt::format("render {}", pass + 1)
                                                             : phaseName("render", pass, f.passes));
  Image image = renderImage(f.ctx, f.render, f.stats.rays);
  endPhase(f.options.progress);
  if (f.ctx.lookup) f.stats.cacheLazyCells = f.ctx.lookup->lazyCells();
  Image& sum = f.result.image;
  if (f.passes > 1) f.spread.add(image, pass, probe ? &f.smoothing : nullptr);
  if (pass == 0) sum = std::move(image);
  else for (size_t i = 0; i < image.pixels.size(); ++i) sum.pixels[i] += image.pixels[i];
  if (pass > 0) for (size_t i = 0; i < image.coverage.size(); ++i) sum.coverage[i] += image.coverage[i];
  f.stats.time.render += phase.seconds();
  f.done = pass + 1;
  if (f.options.afterPass) f.options.afterPass(f.done, sum, f.spread.estimate());
}

// Whether the budget stops the frame after the pass just done (and why, in the stats).
bool budgetStops(FrameRun& f) {
  if (!f.budgeted) return false;
  const double now = f.clock();
  const BudgetState state{f.done, now, now - f.passStart, f.spread.estimate()};
  f.passStart = now;
  std::string stop = budgetStop(f.options.budget, state);
  if (stop.empty()) return false;
  f.stats.budgetStop = std::move(stop);
  return true;
}

// A tile's share of the error figure: what the merge needs to pool it (TileError).
void keepTileError(FrameRun& f, const ErrorEstimate& e) {
  TileError& t = f.result.tileError;
  t.source = e.source;
  t.count = e.count;
  if (e.source == ErrorSource::Samples) t.standardError = f.sampleSpread;
  if (e.source == ErrorSource::Passes) {
    t.even = f.spread.evenSum();
    t.odd = f.spread.oddSum();
    t.checkpoint = f.spread.checkpoint();
    t.smoothing = f.spread.smoothingSums();
  }
  t.emitters = f.emitters;
  if (e.source == ErrorSource::Probes) {
    t.probeSquareSum = e.noiseRmse * e.noiseRmse * double(f.options.bounds->pixels());
    t.probed = e.count;
  }
}

// The image as the mean of its passes, and its error estimate.
void finishFrame(FrameRun& f) {
  RenderStats& stats = f.stats;
  RenderResult& result = f.result;
  const FrameOptions& options = f.options;
  stats.passes = f.done;
  if (f.budgeted) stats.budget = describeBudget(options.budget);
  // Progressive passes are independent estimates: their mean is the image.
  if (f.done > 1) {
    for (Color& c : result.image.pixels) c /= static_cast<float>(f.done);
    for (float& a : result.image.coverage) a /= static_cast<float>(f.done);
  }
  if (f.needsLight && !options.tracePixel) {
    // One pass of one sample (the pixel centres) has no spread: probes beside it measure
    // its error, at every pixel for the error view; their samples count as render time.
    Image probed;
    const bool probes = f.done == 1 && !f.render.standardError;
    const bool errorView = options.derived == DerivedView::Error;
    Stopwatch probing;
    const PixelBounds* bounds = options.bounds ? &*options.bounds : nullptr;
    stats.error = f.done > 1 ? f.spread.estimate()
                  : probes   ? probeError(f.ctx, result.image, f.render.aov, errorView ? &probed : nullptr, bounds)
                             : sampleError(f.sampleSpread, f.scene.camera.spp, f.emitters);
    if (probes) stats.time.render += probing.seconds();
    if (bounds) keepTileError(f, stats.error);
    for (MapKind k : kAllMaps) stats.error.sharedMaps = stats.error.sharedMaps || stats.stored[k] > 0;
    // The derived views, written in the beauty's place.
    if (errorView) {
      result.image = f.done > 1 ? f.spread.standardError() : probes ? std::move(probed) : std::move(f.sampleSpread);
    }
    if (options.derived == DerivedView::Bias) result.image = f.spread.bias();
    if (options.derived == DerivedView::Spp) result.image = sampleCounts(f);
  }
  if (options.findEmitters) result.emitters = f.emitters;
  stats.photonMapBytes = std::max<uint64_t>(stats.photonMapBytes, f.stage.bytes() + f.later.bytes());
}

}  // namespace

void renderFrame(const Scene& scene, const SceneAssets& assets, PhotonStage& stage,
                 const FrameOptions& options, RenderResult& result) {
  // A SIGTERM that came during an earlier frame of this process (a batch's) stops the next.
  if (terminationRequested()) throw Terminated{"SIGTERM: stopped before the next frame"};
  FrameRun f(scene, assets, stage, options, result);
  // Between passes, SIGTERM saves the passes instead of killing them.
  // The spp view counts samples of this run's passes only: it starts at pass 1.
  const bool resumable = !options.resume.path.empty() && f.passes > 1 && !options.tracePixel &&
                         options.derived != DerivedView::Spp;
  std::optional<TermDeferral> deferTerm;
  if (resumable) {
    deferTerm.emplace();
    resumeFrame(f);
  }
  for (int pass = f.first; pass < f.passes; ++pass) {
    bindMaps(f, mapsForPass(f, pass), pass);
    prepareLookups(f, pass);
    if (options.tracePixel) {
      result.rayTree = tracePixel(f.ctx, options.tracePixel->first, options.tracePixel->second);
      f.done = 1;
      break;
    }
    if (pass == f.first) findEmitters(f);
    renderPass(f, pass);
    termHookAfterPass(f.done);
    if (budgetStops(f)) break;
    if (resumable && f.done < f.passes && terminationRequested()) saveAndStop(f);
  }
  finishFrame(f);
}

}  // namespace penumbra
