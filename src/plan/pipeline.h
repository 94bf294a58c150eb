// One render from scene file to image file (penumbra render), on the render session.
#pragma once
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
};

struct RenderResult {
  Image image;
  RenderStats stats;
  RayTree rayTree;  // filled for tracePixel requests
  std::vector<std::string> notes;  // things the user should know ("no point lights: ...")
  ResourceEstimate estimate;       // made before any allocation (plan/resource_estimate.h)
};

RenderResult runRender(const RenderRequest& request);

}  // namespace penumbra
