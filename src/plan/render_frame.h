// The stage after the photons: one frame rendered from built photon maps and the
// scene's assets (plan/scene_assets.h), with its precomputed lookups and progressive passes.
#pragma once
#include "plan/photon_stage.h"
#include "plan/pipeline.h"
#include "plan/render_budget.h"
#include "plan/scene_assets.h"
#include "core/progress.h"
#include "core/pixel_bounds.h"
#include <functional>
#include <memory>
#include <optional>

namespace penumbra {

struct FrameOptions {
  Aov aov = Aov::Beauty;
  PhotonNeeds needs;    // the plan's photon passes, for progressive passes >= 1
  MapCounts budgets;   // ... and their photons per pass
  // The plan's decisions for the tracer (choicesOf), and photons.lookup as planned.
  FrameChoices choices;
  bool precomputed = false;
  std::optional<std::pair<int, int>> tracePixel;
  ProgressPhases* progress = nullptr;  // the command's display; null: none
  // Passes until the budget is met instead of photons.passes (at least 2).
  RenderBudget budget;
  // The job's seconds so far, read between passes on the calling thread; empty: the
  // wall clock since the frame began (the session adds the job's earlier stages;
  // tests give a deterministic clock).
  std::function<double()> clock;
  // Set: the image written is a per-pixel figure of the beauty's render (core/view.h).
  DerivedView derived = DerivedView::None;
  // Set: RenderResult::emitters holds the pixels that see an emitter, even for a frame
  // whose error figure does not need them.
  bool findEmitters = false;
  // Set: only these pixels are rendered (a tile); the error figure is the tile's share
  // (RenderResult::tileError), for the merge to pool.
  std::optional<PixelBounds> bounds;
  // Called after each pass on the calling thread with the passes done, their sum and
  // the estimate so far (tests compare a prefix of passes with the whole).
  std::function<void(int passes, const Image& sum, const ErrorEstimate& error)> afterPass;
  // A progressive frame whose passes a later run may continue (plan/saved_passes.h):
  // SIGTERM saves its finished passes to `path` between passes and throws Terminated;
  // a run with the same `identity` starts after them. Empty path: SIGTERM kills as
  // anywhere else. `discard` (--force): the saved passes are removed, not read.
  struct Resume {
    std::string path, identity;
    bool discard = false;
  } resume;
};

// Renders every pass of `scene` into result.image (or its ray tree), pass 0 from
// `stage`; later physical passes emit their own photons. Fills result.stats'
// photon, lookup, ray and render fields (not load, BVH or write).
void renderFrame(const Scene& scene, const SceneAssets& assets, PhotonStage& stage,
                 const FrameOptions& options, RenderResult& result);

}  // namespace penumbra
