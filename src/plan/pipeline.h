// One render from scene file to image file (penumbra render), on the render session.
#pragma once
#include "core/progress.h"
#include "plan/render_budget.h"
#include "plan/render_plan.h"
#include "plan/resource_estimate.h"
#include "io/scene_loader.h"
#include "io/tone_map.h"
#include "core/image.h"
#include "core/ray_record.h"
#include <functional>
#include "core/stats.h"
#include <functional>
#include <optional>
#include <string>
#include <utility>
#include <vector>

namespace penumbra {

struct RenderRequest {
  std::string scenePath;
  std::string outputPath;               // empty: keep the image in memory only
  std::vector<std::string> overrides;   // --set k=v, applied in order
  int threads = 0;                      // 0 = all cores
  std::string aov;  // empty: the scene's render.aov
  std::optional<std::pair<int, int>> tracePixel;  // record this pixel's ray tree instead
  // The command's progress display; null: none.
  ProgressPhases* progress = nullptr;
  // Files the caller writes after the render (--stats): checked with -o before any work.
  std::vector<std::string> statsPaths;
  uint64_t maxMemoryBytes = 0;  // --max-memory; 0 = the memory available when it starts
  PlanOverrides plan;  // --enable / --disable PASS
  DisplayOptions display;  // --exposure, --tonemap (PNG only)
  // Told before the photons start, e.g. that the job is estimated to take hours.
  std::function<void(const std::string& note)> notice;
  LoadOptions load;  // --no-defaults
  RenderBudget budget;  // --time-limit, --target-error
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
