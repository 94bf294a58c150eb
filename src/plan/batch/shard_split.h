// The split of a batch into shards: jobs that share photon maps kept together
// (the maps built once) and placed largest first on the shard they leave least
// loaded, counting the image module a shard loads once for all its jobs; groups
// larger than a fair share then cut into contiguous runs that fill the shards to
// one level, each run paying the maps.
#pragma once
#include <cstddef>
#include <vector>

namespace penumbra {

// One job's cost in seconds on one thread, from the estimate a render prints.
struct JobCost {
  size_t group = 0;           // jobs with equal photon keys share a group
  double photonSeconds = 0.0;  // the group's maps: paid once by each shard that renders the group
  double frameSeconds = 0.0;   // the job's own frames: every view, every pass
  double moduleSeconds = 0.0;  // the image module it reads textures with: paid once by each shard that needs it
};

struct ShardSplit {
  std::vector<size_t> shardOf;       // per job
  std::vector<double> shardSeconds;  // per shard: its frames, each photon stage it builds and its module
  // Per job, as charged: its frames, and on a group's first job in each shard its maps
  // and the module where that shard lacks it, so a shard's jobs add up to its total.
  std::vector<double> jobSeconds;
  std::vector<size_t> jobsOf(size_t shard) const;  // in job order
};

// Deterministic: equal costs give an equal split on every machine.
ShardSplit splitShards(const std::vector<JobCost>& jobs, size_t count);

}  // namespace penumbra
