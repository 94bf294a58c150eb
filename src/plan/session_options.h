// The options every job of a command shares (threads, memory, the plan's overrides,
// budgets, loading, -D, the stage cache and map files, progress): declared for the command line
// once (cli/session_args) and embedded by value in every request.
#pragma once
#include "core/progress.h"
#include "io/scene_loader.h"
#include "plan/render_budget.h"
#include "plan/render_plan.h"
#include <cstdint>
#include <functional>
#include <string>
#include <vector>

namespace penumbra {

// Photon stages a session keeps for later jobs by default (batch's --map-cache).
constexpr uint64_t kStageCacheBytes = 4ull << 30;

struct SessionOptions {
  int threads = 0;                      // worker threads, 0 = all cores
  uint64_t maxMemoryBytes = 0;          // --max-memory; 0 = the memory available
  uint64_t stageCacheBytes = kStageCacheBytes;  // photon stages kept for later jobs (LRU)
  PlanOverrides plan;                   // --enable / --disable, for every job
  // --time-limit / --target-error: each request's runner gives it to its jobs
  // (a batch job's own budget yields to it field by field).
  RenderBudget budget;
  LoadOptions load;  // --no-defaults, --camera: how a model scene gets its camera and sky
  // --map-dir: photon stages are loaded from files there by key, or built and written
  // there (plan/map_file.h); empty: built in the process only.
  std::string mapDir;
  bool force = false;  // --force: a progressive frame's saved passes are discarded, not resumed
  // -D and the options that stand for scene values (--gate), applied to every job
  // before the job's own overrides (RenderSession::plan).
  std::vector<std::string> overrides;
  ProgressPhases* progress = nullptr;   // the command's display; null: none
  // Told on the session's thread, e.g. that a job is estimated to take hours.
  std::function<void(const std::string& note)> notice;
};

// The session's overrides, then the job's `own`: what a job's scene is loaded with.
std::vector<std::string> jobOverrides(const SessionOptions& options, const std::vector<std::string>& own);

// The scene at `path` with jobOverrides, loaded as a job's would be (the memory
// limit, --no-defaults) but not planned: a command that only inspects it.
Scene loadJobScene(const std::string& path, const SessionOptions& options, const std::vector<std::string>& own = {});

}  // namespace penumbra
