// The batch loop's state, shared by its steps (plan/batch/batch_run.cpp) and its
// choice of this process's jobs (plan/batch/batch_shard_choice.cpp).
#pragma once
#include "plan/batch/batch_run.h"
#include "plan/batch/job_state.h"
#include "plan/batch/shard_split.h"
#include "plan/render_session.h"
#include <string>
#include <vector>

namespace penumbra {

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

// One runBatch: each step a method, in the order run() calls them.
class BatchRun {
 public:
  explicit BatchRun(const BatchRequest& req) : req_(req), session_(req.session), jobs_(req.jobs.size()) {}
  BatchOutcome run();

 private:
  // What each job writes and its stamp, from the jobs file alone.
  void stampJobs();
  // The steps of the request's mode, from the choice of jobs to their renders.
  void runSteps();
  // Every job costed and split into req_.planShards shards (BatchMode::PlanShards).
  void planShards();
  // The indices of the jobs this process takes.
  std::vector<size_t> chooseShard();
  // Each job's verdict from its outputs; returns those not up to date.
  std::vector<size_t> judge(const std::vector<size_t>& mine);
  void reportStatus(const std::vector<size_t>& mine);
  // BVH, light split and the photon estimate of the jobs to render, before any photon.
  void prepareAll(const std::vector<size_t>& todo);
  void renderAll(const std::vector<size_t>& mine);
  void renderOne(PreparedJob& p, size_t j, BatchJobResult& r, std::vector<PhotonStageKey>& storedKeys);

  void fail(PreparedJob& p, const std::string& why, bool input);
  void report(size_t done, size_t total, const std::string& job, const char* phase) const {
    if (req_.progress) req_.progress({done, total, job, phase, clock_.wallSeconds()});
  }
  // Loads, plans and admits the job's views; `forRender` also makes its output folders.
  void plan(PreparedJob& p, bool forRender);
  void planAll(const std::vector<size_t>& which, bool forRender);
  std::vector<JobCost> costs(const std::vector<size_t>& which);
  void checkApart() const;
  std::vector<size_t> allJobs() const;
  std::vector<std::string> jobNames() const;
  BatchJobResult row(size_t j) const;
  void finish();

  const BatchRequest& req_;
  const CpuSpan clock_;
  RenderSession session_;
  std::vector<PreparedJob> jobs_;
  std::vector<bool> builtScene_;  // the job's prepare built its BVH
  BatchOutcome out_;
};

}  // namespace penumbra
