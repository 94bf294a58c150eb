// One render from scene file to image file (penumbra render), on the render session.
#pragma once
#include "plan/frame_tiles.h"
#include "plan/session_options.h"
#include "plan/resource_estimate.h"
#include "io/tone_map.h"
#include "core/image.h"
#include "core/ray_record.h"
#include "core/stats.h"
#include <functional>
#include <optional>
#include <string>
#include <utility>
#include <vector>

namespace penumbra {

struct RenderRequest {
  SessionOptions session;               // threads, memory, plan, budget, -D, progress, notice
  std::string scenePath;
  std::string outputPath;               // empty: keep the image in memory only
  // The render's own overrides (--seed, --spp, --gate), after session.overrides.
  std::vector<std::string> overrides;
  std::string aov;  // empty: the scene's render.aov
  std::optional<std::pair<int, int>> tracePixel;  // record this pixel's ray tree instead
  // Files the caller writes after the render (--stats): checked with -o before any work.
  std::vector<std::string> statsPaths;
  DisplayOptions display;  // --exposure, --tonemap (PNG only)
  // The job's wall seconds so far, for the budget's time limit (the render command:
  // the process's age); empty: the session's own account from the job's load.
  std::function<double()> jobClock;
  // --tile / --pixel-bounds: render only that part and write it as a part file (.exr).
  std::optional<TileRequest> tile;
};

// A tile's share of its frame's error figure, which the merge pools (plan/frame_part.h):
// per-pixel images where the figure is a sum over pixels, else the tile's own sums.
struct TileError {
  ErrorSource source = ErrorSource::None;
  int count = 0;         // samples per pixel or passes
  Image standardError;   // Samples: each pixel's standard error
  Image even, odd;       // Passes: the sums of the even and of the odd passes
  PassCheckpoint checkpoint;  // Passes: the bias check's inputs
  SmoothingSums smoothing;    // Passes: the gathers' smoothing probes, where the model probes them
  EmitterMask emitters;       // Passes, Samples: the pixels the lighting's figures leave out
  double probeSquareSum = 0.0;  // Probes: the tile's mean square error times its pixels
  int probed = 0;
};

struct RenderResult {
  Image image;
  RenderStats stats;
  RayTree rayTree;  // filled for tracePixel requests
  std::vector<std::string> notes;  // things the user should know ("no point lights: ...")
  ResourceEstimate estimate;       // made before any allocation (plan/resource_estimate.h)
  TileError tileError;             // a tile of the frame (JobRequest::bounds) that reads light
  EmitterMask emitters;            // FrameOptions::findEmitters: the pixels that see an emitter
  double emitterSeconds = 0.0;     // ... and the wall time they took, where no render time counts it
  bool media = false;              // the scene has a medium: its reports carry the media counters
};

RenderResult runRender(const RenderRequest& request);

}  // namespace penumbra
