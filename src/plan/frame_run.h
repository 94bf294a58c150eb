// One frame's running state, which its passes and its saved passes share: the
// frame loop (plan/render_frame.cpp) and resuming or saving them (plan/frame_resume.cpp).
#pragma once
#include "plan/render_frame.h"
#include "plan/transport_model.h"
#include "gather/lookup_cache/lookup_cache.h"
#include "trace/camera.h"
#include "trace/render.h"
#include "trace/shading.h"
#include "core/adaptive_sampling.h"
#include "core/stats.h"
#include "core/error_estimate.h"
#include <functional>
#include <string>
#include <vector>

namespace penumbra {

// One frame's running state: the context every pass shades with, the maps of the pass
// being rendered, the image sum and spread, and the budget's clock.
struct FrameRun {
  FrameRun(const Scene& s, const SceneAssets& a, PhotonStage& st, const FrameOptions& o, RenderResult& r)
      : scene(s), assets(a), stage(st), options(o), result(r), stats(r.stats), model(transportOf(s)),
        ctx(s, *a.tracer, o.choices), precomputed(o.precomputed) {
    ctx.textures = assets.textures.get();
    ctx.pixelSpread = CameraRays(scene.camera).pixelSpread();
    ctx.hasGlass = sceneHasGlass(scene);
    ctx.classicScale = stage.classicScale;
    const ShadowPhotonMap& shadow = stage.maps.get<MapKind::Shadow>();
    ctx.maps.get<MapKind::Shadow>() = shadow.size() > 0 ? &shadow : nullptr;  // pass 0's, for every pass
    for (const std::string& n : stage.notes) result.notes.push_back(n);
    if (stage.emitted[MapKind::Indirect] > 0 && stage.maps.get<MapKind::Indirect>().empty()) {
      result.notes.push_back("indirect photons requested but none stored (every p_r and p_t is 0?): "
                             "using the ambient term");
    }
    needsLight = readsLight(options.aov);
    budgeted = options.budget.any() && needsLight && !options.tracePixel;
    fresh = model.freshPhotonsEachPass();
    // --trace-pixel traces the first sample of the render's own sequence, in one pass.
    // A budget's passes sample as any progressive render does, so its image equals the
    // render with photons.passes set to the passes it ran.
    ctx.passes = static_cast<uint32_t>(budgeted ? kBudgetMaxPasses : model.passes(scene, options.aov));
    passes = options.tracePixel ? 1 : static_cast<int>(ctx.passes);
    clock = options.clock ? options.clock : [this] { return wall.seconds(); };
    render.aov = options.aov;
    render.bounds = options.bounds;
    if (options.bounds) spread.keepCheckpoint();
    if (needsLight && passes == 1 && scene.camera.spp > 1) render.standardError = &sampleSpread;
    // A tile cannot know the whole frame's error, which the rule measures pixels against.
    adaptive = adaptiveSampling(scene.render) && needsLight && !options.tracePixel && !options.bounds &&
               passes > kAdaptiveFirstPass;
    rule = adaptiveRule(scene.render, scene.camera.spp);
    // The volume map's beam estimate has no probe: a scene with media keeps the drift check.
    probing = needsLight && !options.tracePixel && passes >= kBiasMinPasses && o.choices.integrator->probesSmoothing &&
              !scene.hasMedia();
    if (options.derived == DerivedView::Spp) samples.assign(size_t(scene.camera.width) * scene.camera.height, 0);
    passStart = clock();
  }
  FrameRun(const FrameRun&) = delete;
  FrameRun& operator=(const FrameRun&) = delete;

  const Scene& scene;
  const SceneAssets& assets;
  PhotonStage& stage;  // pass 0's maps (and the gate's, for every pass)
  const FrameOptions& options;
  RenderResult& result;
  RenderStats& stats;
  const TransportModel& model;
  ShadingContext ctx;
  bool precomputed = false, needsLight = false, budgeted = false, fresh = false;
  int passes = 1, done = 0;
  int first = 0;  // the first pass this run renders: after the saved ones
  const Stopwatch wall;
  std::function<double()> clock;
  double passStart = 0.0;
  LookupCache cache;   // a later pass's own lookups
  PhotonStage later;   // the maps of physical passes >= 1 (fresh photons each)
  RenderOptions render;
  PassSpread spread;
  Image sampleSpread;  // one pass: its samples' standard error per pixel
  bool probing = false;  // the passes' gathers probe their smoothing bias (probesSmoothing)
  Image smoothing;       // ... this pass's, per pixel
  EmitterMask emitters;  // the pixels that see an emitter (the lighting's figures leave them out)
  bool adaptive = false;
  AdaptiveRule rule;
  std::vector<uint16_t> extra;    // this pass's extra samples per pixel
  std::vector<uint32_t> samples;  // the spp view: each pixel's camera samples so far
};

// Continues the frame after its saved passes when they are this frame's (a note says
// so, or why they are not used); --force removes them instead.
void resumeFrame(FrameRun& f);
// SIGTERM came: the finished passes are saved for a later run, and the frame stops.
[[noreturn]] void saveAndStop(FrameRun& f);

}  // namespace penumbra
