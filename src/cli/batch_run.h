// penumbra batch: renders many jobs in one process, sharing the loaded scene,
// BVH and textures between jobs of the same geometry and the photon maps between
// jobs whose photon inputs are equal (plan/reuse_key.h), in an LRU cache with a
// byte cap; skips jobs whose outputs are up to date; reports every job.
#pragma once
#include "cli/batch_jobs.h"
#include "core/progress.h"
#include "io/load_limits.h"
#include "plan/render_session.h"
#include <functional>
#include <string>
#include <vector>

namespace penumbra {

struct BatchRequest {
  std::vector<BatchJob> jobs;
  std::vector<std::string> extraInputs;  // the jobs file: its edits make every output stale
  int threads = 0;
  bool force = false;       // render even jobs whose outputs are up to date
  bool keepGoing = false;   // a job that fails validation is reported, not fatal
  uint64_t mapCacheBytes = kStageCacheBytes;  // photon maps kept for later jobs (LRU)
  uint64_t maxMemoryBytes = 0;  // --max-memory; 0 = the memory available
  PlanOverrides plan;           // --enable / --disable, for every job
  // Called on the batch's own thread with one line per job and phase.
  std::function<void(const std::string& line)> progress;
  ProgressPhases* phases = nullptr;  // the phases inside each render; null: none
};

struct BatchJobResult {
  std::string name;
  std::string status;   // "rendered", "up to date", "failed: ..."
  std::string reused;   // "scene", "photons", "scene+photons" or "-"
  double seconds = 0.0;
  std::vector<std::string> outputs;
};

struct BatchOutcome {
  std::vector<BatchJobResult> jobs;
  size_t failed = 0, rendered = 0, upToDate = 0;
  size_t sceneBuilds = 0, photonBuilds = 0, photonReuses = 0, evictions = 0;
  uint64_t peakCacheBytes = 0;
  double seconds = 0.0;
};

// Validates every job (InputError naming the job unless keepGoing), then renders.
BatchOutcome runBatch(const BatchRequest& request);

// A job's estimated cost for sharding, in nanoseconds: camera samples of every view
// plus photons.
double jobCost(const BatchJob& job, const LoadLimits& limits);

// The summary table printed after a batch.
std::string batchSummary(const BatchOutcome& outcome);

}  // namespace penumbra
