// A batch: renders many jobs in one process, sharing the loaded scene,
// BVH and textures between jobs of the same geometry and the photon maps between
// jobs whose photon inputs are equal (plan/reuse_key.h), in an LRU cache with a
// byte cap; skips jobs whose outputs are up to date (plan/batch/job_state.h)
// without loading their scenes; splits a file into shards; reports every job.
#pragma once
#include "core/cpu_time.h"
#include "plan/batch/batch_shards.h"
#include "plan/render_budget.h"
#include "plan/session_options.h"
#include <functional>
#include <optional>
#include <string>
#include <vector>

namespace penumbra {

struct BatchOutput {
  std::string view;  // "beauty", "depth", ...; "" = the scene's render.aov
  std::string path;  // an image file; several views may share one layered .exr
};

// Tile `index` (1-based) of `count` of a job's frame (a jobs file's "tiles"): its
// outputs are part files; `frame` holds the whole frame's outputs, whose job the
// parts' merge stands for.
struct BatchTile {
  int index = 1, count = 1;
  std::vector<BatchOutput> frame;
};

struct BatchJob {
  std::string name;                    // "orbit_3", "fig03_shadows": unique in the batch
  std::string scene;                   // resolved path
  std::vector<std::string> overrides;  // the batch's "set", then the job's, then the orbit's (after -D)
  std::vector<BatchOutput> outputs;    // one per view
  std::string where;                   // "jobs[2] (orbit 3)": names the job in messages
  RenderBudget budget;                 // "time_limit", "target_error" or the command line's
  std::optional<BatchTile> tile;       // set: this job renders one tile of the frame
};

// Where a batch is: `done` of `total` jobs finished after `seconds`; `job` in `phase`.
struct BatchProgress {
  size_t done = 0, total = 0;
  std::string job;
  const char* phase = "";
  double seconds = 0.0;
};

// What a batch run does with its jobs.
enum class BatchMode {
  Render,      // render the jobs not up to date
  MapsOnly,    // emit their photons into --map-dir files (a farm's prepass), render nothing
  ListShard,   // name the shard's jobs and their estimates
  PlanShards,  // split every job into planShards shards (BatchOutcome::split)
  Status,      // say of every job whether it is up to date, and why not
};

struct BatchRequest {
  // Every job's: threads, memory, the map cache, the plan, -D (before each job's own),
  // the budget (over each job's own, field by field), the phases inside each render.
  SessionOptions session;
  std::vector<BatchJob> jobs;  // the whole jobs file, also when one shard renders
  BatchMode mode = BatchMode::Render;
  size_t planShards = 0;  // PlanShards: how many
  // Set: only this shard's jobs, from `shardFile` when given (no other job is
  // loaded), else from a split of every job made here. A shard file without a
  // shard (Status): every job, each with its shard.
  std::optional<ShardChoice> shard;
  std::optional<ShardFile> shardFile;
  std::vector<std::string> protectedFiles;  // no output may overwrite these (the jobs file)
  bool force = false;       // render even jobs whose outputs are up to date
  bool keepGoing = false;   // a job that fails validation is reported, not fatal
  // Told on the batch's own thread as each job is loaded ("load"), starts ("render") and ends ("done").
  std::function<void(const BatchProgress&)> progress;
};

struct BatchJobResult {
  std::string name;
  std::string status;   // "rendered", "up to date", "missing: ...", "stale: ...", "failed: ..."
  std::string reused;   // "scene", "photons", "scene+photons" or "-"
  double seconds = 0.0;
  double estimate = 0.0;  // seconds on one thread, where the job was costed (shards)
  size_t shard = 0;       // 0-based, with a shard
  CpuTiming cpu;  // the process's CPU time over the same span
  std::vector<std::string> outputs;
};

struct BatchOutcome {
  std::vector<BatchJobResult> jobs;  // the jobs rendered or checked: the shard's, else all
  std::vector<size_t> shardJobs;     // with a shard: indices into BatchRequest::jobs
  std::string shardLabel;            // "shard 1/4 (SLURM_ARRAY_TASK_ID=0)"; "" without one
  size_t shardCount = 0;             // shards the jobs fall into (BatchJobResult::shard); 0: none
  ShardFile split;                   // PlanShards
  size_t failed = 0, rendered = 0, upToDate = 0, notUpToDate = 0;
  size_t sceneReads = 0, sceneBuilds = 0, photonBuilds = 0, photonReuses = 0, evictions = 0;
  size_t mapLoads = 0, mapWrites = 0;  // photon map files (--map-dir) read and written
  uint64_t peakCacheBytes = 0;
  double seconds = 0.0;
  CpuTiming cpu;  // over the whole batch
  // The jobs' load and plan notes, each once; the contended note when rendered jobs had too little CPU.
  std::vector<std::string> notes;
};

// Decides which jobs are up to date from their outputs, then loads, validates
// (InputError naming the job unless keepGoing) and renders the others.
BatchOutcome runBatch(const BatchRequest& request);

}  // namespace penumbra
