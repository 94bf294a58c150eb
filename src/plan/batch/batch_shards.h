// How a task names its shard: `--shard I/N` (1-based), a scheduler's 0-based
// index (`--shard-index env|I --shard-count N`), and the split written once by
// `--plan-shards` and read by every task (`--shard-file`).
#pragma once
#include <cstddef>
#include <string>
#include <vector>

namespace penumbra {

// "2/4" -> {1, 4} (1-based on the command line); throws InputError.
std::pair<size_t, size_t> parseShard(const std::string& text);

// The variables a scheduler sets to a task's 0-based index, in the order read:
// Slurm arrays, Kubernetes Indexed Jobs, AWS Batch array jobs.
inline constexpr const char* kShardIndexVariables[] = {"SLURM_ARRAY_TASK_ID", "JOB_COMPLETION_INDEX",
                                                        "AWS_BATCH_JOB_ARRAY_INDEX"};

// A task's shard: `index` of `count`, 0-based, and how it was named for logs
// ("shard 1/4 (SLURM_ARRAY_TASK_ID=0)").
struct ShardChoice {
  size_t index = 0, count = 1;
  std::string label;
};
// `--shard-index` as given: "env" reads the first of kShardIndexVariables that is
// set; else a number. Refused (InputError naming the variable) when missing, not a
// number, or >= count; count never comes from the environment.
ShardChoice shardFromIndex(const std::string& index, size_t count);
ShardChoice shardFromSlash(const std::string& text);  // --shard I/N

// A split written by `batch --plan-shards N -o FILE`: each shard's jobs by name,
// with the estimated seconds of each.
struct ShardFile {
  std::string jobsFile;  // as given to --plan-shards, for messages
  struct Job {
    std::string name;
    double seconds = 0.0;
  };
  std::vector<std::vector<Job>> shards;
  std::vector<double> seconds;  // per shard, photon stages included
};
std::string shardFileText(const ShardFile& file);
// Throws InputError naming the file and JSON path.
ShardFile readShardFile(const std::string& path);

// The jobs (indices into `names`, in order) of shard `index` of `file`. A job the
// file does not name (appended since) goes to the shard with the least seconds,
// counting the file's mean job for each placed, so every task places it alike;
// `unplaced` counts them.
std::vector<size_t> jobsOfShardFile(const ShardFile& file, const std::vector<std::string>& names, size_t index,
                                    size_t* unplaced = nullptr);

}  // namespace penumbra
