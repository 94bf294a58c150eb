// Which jobs this process takes: all of them, its shard's from a shard file (no
// other job loaded), or its shard of a split of every job costed here; and the
// split itself (--plan-shards).
#include "plan/batch/batch_loop.h"
#include "plan/batch/job_cost.h"
#include "core/error.h"
#include <fmt/format.h>
#include <algorithm>

namespace penumbra {

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
        for (PlannedJob& v : p.views) session_.prepare(v, RenderSession::PrepareFor::Photons);
        tracer = session_.geometry(p.views.front()).tracer.get();
      } catch (const std::exception&) {
        // Refused on this machine (its memory): costed from the bounds.
      }
      c = jobCostOf(p.views, tracer);
    }
    const auto known = std::find(keys.begin(), keys.end(), key);
    c.group = static_cast<size_t>(known - keys.begin());
    // A group's maps are charged to its first job, as one process pays them once.
    p.estimate = c.frameSeconds + (known == keys.end() ? c.photonSeconds + c.moduleSeconds : 0.0);
    if (known == keys.end()) keys.push_back(key);
    out.push_back(c);
  }
  return out;
}

// The indices of the jobs this process takes: all, its shard's in the shard file
// (nothing else loaded), or its shard of a split of every job made here.
std::vector<size_t> BatchRun::chooseShard() {
  const std::vector<size_t> all = allJobs();
  if (!req_.shard && req_.shardFile) {
    // Every shard's jobs (--status of a whole farm): each job named by its shard.
    const std::vector<std::string> names = jobNames();
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
    const std::vector<std::string> names = jobNames();
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
  for (size_t k = 0; k < all.size(); ++k) jobs_[all[k]].estimate = split.jobSeconds[k];
  out_.split.seconds = split.shardSeconds;
  return split.jobsOf(req_.shard->index);
}

void BatchRun::planShards() {
  const std::vector<size_t> all = allJobs();
  planAll(all, false);
  checkApart();
  const ShardSplit split = splitShards(costs(all), req_.planShards);
  for (size_t k = 0; k < all.size(); ++k) jobs_[all[k]].estimate = split.jobSeconds[k];
  out_.split.seconds = split.shardSeconds;
  out_.split.shards.resize(split.shardSeconds.size());
  for (size_t j : all) {
    jobs_[j].shard = split.shardOf[j];
    out_.split.shards[split.shardOf[j]].push_back({jobs_[j].job->name, jobs_[j].estimate});
    out_.jobs.push_back(row(j));
  }
}

}  // namespace penumbra
