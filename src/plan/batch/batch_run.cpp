// The batch loop: decide from each job's outputs whether it is up to date (no
// scene loaded), choose the shard's jobs, then load, plan and admit the jobs to
// render before the first of them renders through the render session, which
// shares scenes and photon stages between jobs.
#include "plan/batch/batch_loop.h"
#include "plan/batch/job_cost.h"
#include "plan/batch/job_render.h"
#include "plan/batch/job_state.h"
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

namespace fs = std::filesystem;

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

BatchOutcome BatchRun::run() {
  stampJobs();
  runSteps();
  finish();
  return out_;
}

void BatchRun::runSteps() {
  if (req_.mode == BatchMode::PlanShards) return planShards();
  const std::vector<size_t> mine = chooseShard();
  checkApart();
  if (req_.shard) out_.shardJobs = mine;
  if (req_.mode == BatchMode::ListShard) {
    for (size_t j : mine) out_.jobs.push_back(row(j));
    return;
  }
  // Up to date or not is decided before any job writes.
  const std::vector<size_t> todo = judge(mine);
  if (req_.mode == BatchMode::Status) return reportStatus(mine);
  // The jobs to render loaded, planned and admitted (a scene file read once).
  planAll(todo, req_.mode == BatchMode::Render);
  checkApart();
  prepareAll(todo);
  renderAll(mine);
}

void BatchRun::stampJobs() {
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
}

std::vector<size_t> BatchRun::judge(const std::vector<size_t>& mine) {
  size_t checked = 0;
  std::vector<size_t> todo;
  for (size_t j : mine) {
    PreparedJob& p = jobs_[j];
    if (!p.error.empty()) continue;
    report(checked++, mine.size(), p.job->name, "check");
    p.verdict = req_.force ? OutputsVerdict{JobState::Stale, "--force", {}} : judgeOutputs(p.outputs, p.stamp);
    if (p.verdict.state != JobState::UpToDate) todo.push_back(j);
  }
  return todo;
}

void BatchRun::reportStatus(const std::vector<size_t>& mine) {
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
}

void BatchRun::prepareAll(const std::vector<size_t>& todo) {
  builtScene_.assign(jobs_.size(), false);
  size_t prepared = 0;
  for (size_t j : todo) {
    PreparedJob& p = jobs_[j];
    report(prepared++, todo.size(), p.job->name, "prepare");
    if (!p.error.empty()) continue;
    const size_t builds = session_.sceneBuilds();
    try {
      const auto what = req_.mode == BatchMode::MapsOnly ? RenderSession::PrepareFor::Photons
                                                         : RenderSession::PrepareFor::Frames;
      for (PlannedJob& v : p.views) session_.prepare(v, what);
    } catch (const InputError& e) {
      fail(p, e.what(), true);
    } catch (const std::exception& e) {
      p.error = e.what();  // out of memory or an Embree failure: this job fails, the batch goes on
    }
    builtScene_[j] = session_.sceneBuilds() > builds;
  }
}

void BatchRun::renderAll(const std::vector<size_t>& mine) {
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
        report(done, mine.size(), p.job->name, req_.mode == BatchMode::MapsOnly ? "photons" : "render");
        renderOne(p, j, r, storedKeys);
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
}

// Renders the job (or writes its maps) and says so in `r`; throws what fails it.
void BatchRun::renderOne(PreparedJob& p, size_t j, BatchJobResult& r, std::vector<PhotonStageKey>& storedKeys) {
  // The disk may have filled (or the folder gone) since the jobs were checked:
  // fail now rather than after the render.
  if (req_.mode == BatchMode::Render) for (const std::string& path : p.outputs) checkImageOutputPath(path);
  std::vector<std::string> reused;
  if (!builtScene_[j]) reused.push_back("scene");
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
}

BatchJobResult BatchRun::row(size_t j) const {
  BatchJobResult r;
  r.name = jobs_[j].job->name;
  r.outputs = jobs_[j].outputs;
  r.estimate = jobs_[j].estimate;
  r.shard = jobs_[j].shard;
  return r;
}

std::vector<size_t> BatchRun::allJobs() const {
  std::vector<size_t> all(jobs_.size());
  std::iota(all.begin(), all.end(), size_t(0));
  return all;
}

std::vector<std::string> BatchRun::jobNames() const {
  std::vector<std::string> names;
  for (const BatchJob& j : req_.jobs) names.push_back(j.name);
  return names;
}

void BatchRun::finish() {
  out_.sceneReads = session_.sceneReads();
  out_.sceneBuilds = session_.sceneBuilds();
  out_.photonBuilds = session_.photonBuilds();
  out_.mapLoads = session_.mapLoads();
  out_.mapWrites = session_.mapWrites();
  out_.evictions = session_.evictions();
  out_.peakCacheBytes = session_.peakStageBytes();
  out_.cpu = clock_.timing(session_.options().threads);
  out_.seconds = out_.cpu.wallSeconds;
}

BatchOutcome runBatch(const BatchRequest& request) { return BatchRun(request).run(); }

}  // namespace penumbra
