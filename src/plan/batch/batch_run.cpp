// The batch loop: decide from each job's outputs whether it is up to date (no
// scene loaded), choose the shard's jobs, then load, plan and admit the jobs to
// render before the first of them renders through the render session, which
// shares scenes and photon stages between jobs.
#include "plan/batch/batch_run.h"
#include "plan/batch/job_cost.h"
#include "plan/batch/job_render.h"
#include "plan/batch/job_state.h"
#include "plan/batch/shard_split.h"
#include "plan/cpu_report.h"
#include "plan/output_safety.h"
#include "plan/render_session.h"
#include "plan/saved_passes.h"
#include "core/error.h"
#include "io/image_io.h"
#include "io/temp_file.h"
#include <fmt/format.h>
#include <algorithm>
#include <filesystem>
#include <numeric>

namespace penumbra {
namespace {

namespace fs = std::filesystem;

struct PreparedJob {
  const BatchJob* job = nullptr;
  std::vector<std::string> outputs;  // each file once (views may share a layered EXR)
  std::string stamp;                 // written into every output: a changed job makes them stale
  std::string frameStamp;            // a tile's: the whole frame's stamp, which its parts share
  OutputsVerdict verdict;            // from the outputs, before anything loads
  std::vector<PlannedJob> views;     // one per output, planned and admitted (jobs to render or cost)
  std::vector<InputRecord> inputs;   // what the views read, as it was when loaded
  double estimate = 0.0;             // seconds on one thread, once costed
  size_t shard = 0;                  // 0-based, where the batch has shards
  std::string error;                 // validation failure (keepGoing)
};

class BatchRun {
 public:
  BatchRun(const BatchRequest& req) : req_(req), session_(req.session), jobs_(req.jobs.size()) {}
  BatchOutcome run();

 private:
  void fail(PreparedJob& p, const std::string& why, bool input);
  void report(size_t done, size_t total, const std::string& job, const char* phase) {
    if (req_.progress) req_.progress({done, total, job, phase, clock_.wallSeconds()});
  }
  // Loads, plans and admits the job's views; `forRender` also makes its output folders.
  void plan(PreparedJob& p, bool forRender);
  void planAll(const std::vector<size_t>& which, bool forRender);
  std::vector<JobCost> costs(const std::vector<size_t>& which);
  std::vector<size_t> chooseShard();
  void checkApart() const;
  void finish(BatchOutcome& out);

  const BatchRequest& req_;
  const CpuSpan clock_;
  RenderSession session_;
  std::vector<PreparedJob> jobs_;
  BatchOutcome out_;
};

void BatchRun::fail(PreparedJob& p, const std::string& why, bool input) {
  p.error = why;
  p.views.clear();
  if (input && !req_.keepGoing) throw InputError("batch job '" + p.job->name + "' (" + p.job->where + "): " + why);
}

void BatchRun::plan(PreparedJob& p, bool forRender) {
  if (!p.error.empty()) return;
  try {
    if (p.views.empty()) {
      JobRequest first;
      first.scenePath = p.job->scene;
      first.overrides = p.job->overrides;
      first.view = p.job->outputs.front().view;
      first.budget = jobBudget(*p.job, req_.session.budget);
      if (p.job->tile) first.tile = TileRequest{p.job->tile->index, p.job->tile->count, std::nullopt};
      p.views.push_back(session_.plan(first));
      for (size_t v = 1; v < p.job->outputs.size(); ++v) {
        p.views.push_back(session_.planView(p.views.front(), p.job->outputs[v].view));
      }
      // Each view's passes file, beside its output (named by view where views share one).
      for (size_t v = 0; v < p.views.size(); ++v) {
        const std::string& path = p.job->outputs[v].path;
        const bool shared = std::count_if(p.job->outputs.begin(), p.job->outputs.end(),
                                          [&](const BatchOutput& o) { return o.path == path; }) > 1;
        p.views[v].request.savedPasses = savedPassesPath(path, shared ? p.views[v].viewName : "");
      }
      for (const std::string& n : p.views.front().notes) {
        if (std::find(out_.notes.begin(), out_.notes.end(), n) == out_.notes.end()) out_.notes.push_back(n);
      }
      p.inputs = recordInputs(p.views.front().inputs);
    }
    if (!forRender) return;
    std::vector<OutputPath> outputs;
    for (const std::string& path : p.outputs) {
      // Folders a jobs file names are made, as -o DIR's is.
      const fs::path folder = fs::path(path).parent_path();
      std::error_code ec;
      if (!folder.empty() && !fs::is_directory(folder, ec)) fs::create_directories(folder, ec);
      if (ec) throw InputError(path + ": cannot create its folder (" + ec.message() + ")");
      outputs.push_back({path, "output", true});
    }
    std::vector<std::string> reads = p.views.front().inputs;
    reads.insert(reads.end(), req_.protectedFiles.begin(), req_.protectedFiles.end());
    checkOutputs(outputs, reads);
  } catch (const InputError& e) {
    fail(p, e.what(), true);
  }
}

void BatchRun::planAll(const std::vector<size_t>& which, bool forRender) {
  size_t done = 0;
  for (size_t j : which) {
    report(done++, which.size(), jobs_[j].job->name, "load");
    plan(jobs_[j], forRender);
  }
  // Every job is planned: what the loads shared is no longer needed.
  session_.forgetLoads();
}

// Each job's cost, with jobs of equal photon keys in one group.
std::vector<JobCost> BatchRun::costs(const std::vector<size_t>& which) {
  std::vector<PhotonStageKey> keys;
  std::vector<JobCost> out;
  for (size_t j : which) {
    PreparedJob& p = jobs_[j];
    PhotonStageKey key;
    JobCost c;
    if (p.views.empty()) {
      key.geometry = "not loaded: " + p.job->name;  // costs nothing, in a group of its own
    } else {
      key = photonKeyOf(p.views);
      const TraceScene* tracer = nullptr;
      try {
        for (PlannedJob& v : p.views) session_.prepare(v);
        tracer = session_.assets(p.views.front()).tracer.get();
      } catch (const std::exception&) {
        // Refused on this machine (its memory): costed from the bounds.
      }
      c = jobCostOf(p.views, tracer);
    }
    const auto known = std::find(keys.begin(), keys.end(), key);
    c.group = static_cast<size_t>(known - keys.begin());
    // A group's maps are charged to its first job, as the split charges them once.
    p.estimate = c.frameSeconds + (known == keys.end() ? c.photonSeconds : 0.0);
    if (known == keys.end()) keys.push_back(key);
    out.push_back(c);
  }
  return out;
}

// No job may write what another writes or reads, whatever their order and shard:
// every job's outputs are known from the file, its inputs once loaded or recorded
// in its outputs, else its scene file.
void BatchRun::checkApart() const {
  std::vector<JobFiles> files;
  for (const PreparedJob& p : jobs_) {
    if (!p.error.empty()) continue;
    std::vector<std::string> reads = !p.views.empty() ? p.views.front().inputs : p.verdict.inputs;
    if (reads.empty()) reads.push_back(p.job->scene);
    files.push_back({p.job->name, p.outputs, reads});
  }
  checkJobsApart(files);
}

// The indices of the jobs this process takes: all, its shard's in the shard file
// (nothing else loaded), or its shard of a split of every job made here.
std::vector<size_t> BatchRun::chooseShard() {
  std::vector<size_t> all(jobs_.size());
  std::iota(all.begin(), all.end(), size_t(0));
  if (!req_.shard && req_.shardFile) {
    // Every shard's jobs (--status of a whole farm): each job named by its shard.
    std::vector<std::string> names;
    for (const BatchJob& j : req_.jobs) names.push_back(j.name);
    for (size_t s = 0; s < req_.shardFile->shards.size(); ++s) {
      for (size_t j : jobsOfShardFile(*req_.shardFile, names, s)) jobs_[j].shard = s;
    }
    out_.shardCount = req_.shardFile->shards.size();
    return all;
  }
  if (!req_.shard) return all;
  out_.shardCount = req_.shard->count;
  for (PreparedJob& p : jobs_) p.shard = req_.shard->index;
  out_.shardLabel = req_.shard->label;
  if (req_.shardFile) {
    std::vector<std::string> names;
    for (const BatchJob& j : req_.jobs) names.push_back(j.name);
    size_t unplaced = 0;
    if (req_.shardFile->shards.size() != req_.shard->count) {
      throw InputError(fmt::format("--shard-count {} but the shard file has {} shards", req_.shard->count,
                                   req_.shardFile->shards.size()));
    }
    std::vector<size_t> mine = jobsOfShardFile(*req_.shardFile, names, req_.shard->index, &unplaced);
    for (const auto& shard : req_.shardFile->shards) {
      for (const ShardFile::Job& fj : shard) {
        auto it = std::find(names.begin(), names.end(), fj.name);
        if (it != names.end()) jobs_[it - names.begin()].estimate = fj.seconds;
      }
    }
    out_.split.seconds = req_.shardFile->seconds;
    if (unplaced > 0) {
      out_.notes.push_back(fmt::format("{} jobs are not in the shard file: each went to the least-loaded shard "
                                       "(plan the shards again to balance them)", unplaced));
    }
    return mine;
  }
  planAll(all, false);
  const ShardSplit split = splitShards(costs(all), req_.shard->count);
  out_.split.seconds = split.shardSeconds;
  return split.jobsOf(req_.shard->index);
}

BatchOutcome BatchRun::run() {
  // 1. What each job writes and its stamp, from the jobs file alone.
  for (size_t j = 0; j < jobs_.size(); ++j) {
    PreparedJob& p = jobs_[j];
    p.job = &req_.jobs[j];
    for (const BatchOutput& o : p.job->outputs) {
      if (std::find(p.outputs.begin(), p.outputs.end(), o.path) == p.outputs.end()) p.outputs.push_back(o.path);
    }
    if (p.outputs.empty()) fail(p, "the job writes no output", true);
    p.stamp = jobStamp(definitionOf(*p.job, req_.session));
    if (p.job->tile) {
      // The merged frame's stamp is the untiled job's: a merge equals its render.
      BatchJob whole = *p.job;
      whole.outputs = p.job->tile->frame;
      whole.tile.reset();
      p.frameStamp = jobStamp(definitionOf(whole, req_.session));
    }
  }
  auto row = [&](size_t j) {
    BatchJobResult r;
    r.name = jobs_[j].job->name;
    r.outputs = jobs_[j].outputs;
    r.estimate = jobs_[j].estimate;
    r.shard = jobs_[j].shard;
    return r;
  };
  if (req_.mode == BatchMode::PlanShards) {
    std::vector<size_t> all(jobs_.size());
    std::iota(all.begin(), all.end(), size_t(0));
    planAll(all, false);
    checkApart();
    const ShardSplit split = splitShards(costs(all), req_.planShards);
    out_.split.seconds = split.shardSeconds;
    out_.split.shards.resize(split.shardSeconds.size());
    for (size_t j : all) {
      out_.split.shards[split.shardOf[j]].push_back({jobs_[j].job->name, jobs_[j].estimate});
      out_.jobs.push_back(row(j));
      out_.jobs.back().shard = split.shardOf[j];
    }
    finish(out_);
    return out_;
  }

  // 2. This process's jobs.
  const std::vector<size_t> mine = chooseShard();
  checkApart();
  if (req_.shard) out_.shardJobs = mine;
  if (req_.mode == BatchMode::ListShard) {
    for (size_t j : mine) out_.jobs.push_back(row(j));
    finish(out_);
    return out_;
  }

  // 3. Up to date or not, from the outputs alone, decided before any job writes.
  size_t checked = 0;
  std::vector<size_t> todo;
  for (size_t j : mine) {
    PreparedJob& p = jobs_[j];
    if (!p.error.empty()) continue;
    report(checked++, mine.size(), p.job->name, "check");
    p.verdict = req_.force ? OutputsVerdict{JobState::Stale, "--force", {}} : judgeOutputs(p.outputs, p.stamp);
    if (p.verdict.state != JobState::UpToDate) todo.push_back(j);
  }
  if (req_.mode == BatchMode::Status) {
    for (size_t j : mine) {
      const PreparedJob& p = jobs_[j];
      BatchJobResult r = row(j);
      if (!p.error.empty()) {
        r.status = "failed: " + p.error;
        ++out_.failed;
      } else if (p.verdict.state == JobState::UpToDate) {
        r.status = jobStateName(p.verdict.state);
        ++out_.upToDate;
      } else {
        r.status = std::string(jobStateName(p.verdict.state)) + ": " + p.verdict.why;
        ++out_.notUpToDate;
      }
      out_.jobs.push_back(r);
    }
    finish(out_);
    return out_;
  }

  // 4. The jobs to render loaded, planned and admitted (a scene file read once).
  planAll(todo, req_.mode == BatchMode::Render);
  checkApart();

  // 5. Prepared (BVH, light split, the photon estimate against the memory limit)
  // before the first photon of any of them.
  std::vector<bool> builtScene(jobs_.size(), false);  // this job's prepare built its BVH
  size_t prepared = 0;
  for (size_t j : todo) {
    PreparedJob& p = jobs_[j];
    report(prepared++, todo.size(), p.job->name, "prepare");
    if (!p.error.empty()) continue;
    const size_t builds = session_.sceneBuilds();
    try {
      for (PlannedJob& v : p.views) session_.prepare(v);
    } catch (const InputError& e) {
      fail(p, e.what(), true);
    } catch (const std::exception& e) {
      p.error = e.what();  // out of memory or an Embree failure: this job fails, the batch goes on
    }
    builtScene[j] = session_.sceneBuilds() > builds;
  }

  // 6. Render (or build the maps), sharing what the keys allow.
  size_t done = 0;
  std::vector<PhotonStageKey> storedKeys;  // --maps-only
  for (size_t j : mine) {
    PreparedJob& p = jobs_[j];
    BatchJobResult r = row(j);
    const CpuSpan jobClock;
    if (!p.error.empty()) {
      r.status = "failed: " + p.error;
    } else if (p.verdict.state == JobState::UpToDate) {
      r.status = jobStateName(JobState::UpToDate);
      ++out_.upToDate;
    } else {
      // A SIGTERM that came as the last job's last pass ended: stop before this one's photons.
      if (terminationRequested()) throw Terminated{"SIGTERM: stopped before job '" + p.job->name + "'"};
      try {
        // The disk may have filled (or the folder gone) since the jobs were checked:
        // fail now rather than after the render.
        if (req_.mode == BatchMode::Render) for (const std::string& path : p.outputs) checkImageOutputPath(path);
        report(done, mine.size(), p.job->name, req_.mode == BatchMode::MapsOnly ? "photons" : "render");
        std::vector<std::string> reused;
        if (!builtScene[j]) reused.push_back("scene");
        JobRender rendered;
        if (req_.mode == BatchMode::MapsOnly) {
          std::vector<const PlannedJob*> views;
          for (const PlannedJob& v : p.views) views.push_back(&v);
          // Each photon key once: an orbit's frames share one file.
          const PhotonStageKey key = photonKeyOf(p.views);
          if (std::find(storedKeys.begin(), storedKeys.end(), key) != storedKeys.end()) {
            r.status = "maps shared";
          } else {
            storedKeys.push_back(key);
            const MapFileOutcome file = session_.storeMaps(views);
            r.status = file.written ? "maps written" : file.loaded ? "maps on disk" : "no photons";
            if (!file.note.empty()) out_.notes.push_back(file.note);
          }
        } else {
          rendered = renderJob(session_, *p.job, p.views, {p.stamp, p.frameStamp, p.inputs});
          out_.notes.insert(out_.notes.end(), rendered.notes.begin(), rendered.notes.end());
          r.status = "rendered";
          ++out_.rendered;
        }
        if (rendered.photonsReused) {
          reused.push_back("photons");
          ++out_.photonReuses;
        }
        r.reused = reused.empty() ? "-" : fmt::format("{}", fmt::join(reused, "+"));
      } catch (const std::exception& e) {
        r.status = std::string("failed: ") + e.what();
      }
    }
    if (r.status.rfind("failed", 0) == 0) ++out_.failed;
    r.cpu = jobClock.timing(session_.options().threads);
    r.seconds = r.cpu.wallSeconds;
    out_.jobs.push_back(r);
    report(++done, mine.size(), p.job->name, "done");
  }
  std::vector<CpuTiming> rendered;
  for (const BatchJobResult& j : out_.jobs) {
    if (j.status == "rendered") rendered.push_back(j.cpu);
  }
  const std::string contended = contendedNote(rendered, "job");
  if (!contended.empty()) out_.notes.push_back(contended);
  finish(out_);
  return out_;
}

void BatchRun::finish(BatchOutcome& out) {
  out.sceneReads = session_.sceneReads();
  out.sceneBuilds = session_.sceneBuilds();
  out.photonBuilds = session_.photonBuilds();
  out.mapLoads = session_.mapLoads();
  out.mapWrites = session_.mapWrites();
  out.evictions = session_.evictions();
  out.peakCacheBytes = session_.peakStageBytes();
  out.cpu = clock_.timing(session_.options().threads);
  out.seconds = out.cpu.wallSeconds;
}

}  // namespace

BatchOutcome runBatch(const BatchRequest& request) { return BatchRun(request).run(); }

}  // namespace penumbra
