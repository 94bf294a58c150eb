// The split of a batch into shards and how a task names its shard: groups of one
// photon key kept together unless larger than a fair share, the largest placed
// first; 0-based scheduler indices from the environment; the shard file's round
// trip and the placement of jobs appended since it was written.
#include "plan/batch/batch_shards.h"
#include "plan/batch/shard_split.h"
#include "core/error.h"
#include "support/scratch_dir.h"
#include <gtest/gtest.h>
#include <algorithm>
#include <cstdlib>
#include <numeric>

namespace penumbra {
namespace {

double maxOverMean(const ShardSplit& s) {
  const double sum = std::accumulate(s.shardSeconds.begin(), s.shardSeconds.end(), 0.0);
  return *std::max_element(s.shardSeconds.begin(), s.shardSeconds.end()) / (sum / double(s.shardSeconds.size()));
}

TEST(BatchShards, AGroupStaysInOneShardAndPaysItsMapsOnce) {
  // Jobs 0..3 share maps of 6 s; jobs 4..7 each have their own maps.
  std::vector<JobCost> jobs;
  for (size_t j = 0; j < 4; ++j) jobs.push_back({0, 6.0, 1.0});
  for (size_t j = 4; j < 8; ++j) jobs.push_back({j, 1.0, 3.0});
  const ShardSplit split = splitShards(jobs, 2);
  for (size_t j = 1; j < 4; ++j) EXPECT_EQ(split.shardOf[j], split.shardOf[0]);
  // The group costs 6 + 4 = 10, each other job 4: 10 + 4 against 12.
  std::vector<double> seconds = split.shardSeconds;
  std::sort(seconds.begin(), seconds.end());
  EXPECT_DOUBLE_EQ(seconds[0], 12.0);
  EXPECT_DOUBLE_EQ(seconds[1], 14.0);
}

TEST(BatchShards, AGroupLargerThanAFairShareIsCutIntoContiguousRuns) {
  // A 64-frame orbit sharing one map, and two other jobs.
  std::vector<JobCost> jobs;
  for (size_t j = 0; j < 64; ++j) jobs.push_back({0, 2.0, 1.0});
  jobs.push_back({1, 0.0, 10.0});
  jobs.push_back({2, 0.0, 10.0});
  const ShardSplit split = splitShards(jobs, 4);
  EXPECT_LE(maxOverMean(split), 1.25);
  // Each shard's orbit frames are one run of consecutive frames.
  for (size_t s = 0; s < 4; ++s) {
    std::vector<size_t> frames;
    for (size_t j : split.jobsOf(s)) if (j < 64) frames.push_back(j);
    for (size_t k = 1; k < frames.size(); ++k) EXPECT_EQ(frames[k], frames[k - 1] + 1) << "shard " << s;
  }
}

TEST(BatchShards, ALargerGroupFillsTheShardsAroundALargeJobToOneLevel) {
  // An 8 s job and a 64-frame orbit of 1 s frames sharing 2 s of maps: 74 s, 18.5 a
  // shard. The orbit fills the three empty shards to 20 (2 + 18 frames each) and the
  // large job's shard with the last 10 frames (8 + 2 + 10): every shard 20 s.
  std::vector<JobCost> jobs = {{0, 0.0, 8.0}};
  for (size_t j = 0; j < 64; ++j) jobs.push_back({1, 2.0, 1.0});
  const ShardSplit split = splitShards(jobs, 4);
  for (double seconds : split.shardSeconds) EXPECT_DOUBLE_EQ(seconds, 20.0);
  EXPECT_EQ(split.jobsOf(split.shardOf[0]).size(), 11u);
}

TEST(BatchShards, TheLargestJobsArePlacedFirst) {
  const std::vector<JobCost> jobs = {{0, 0, 1}, {1, 0, 1}, {2, 0, 1}, {3, 0, 1}, {4, 0, 1}, {5, 0, 5}};
  const ShardSplit split = splitShards(jobs, 2);
  EXPECT_EQ(split.jobsOf(0), (std::vector<size_t>{5}));
  EXPECT_EQ(split.jobsOf(1), (std::vector<size_t>{0, 1, 2, 3, 4}));
  EXPECT_DOUBLE_EQ(maxOverMean(split), 1.0);
}

TEST(BatchShards, JobsThatReadTexturesShareAShardThatLoadsTheModuleOnce) {
  // A 5 s job, and two 2 s textured jobs whose image module costs a shard 1 s: the
  // pair on the other shard pays the module once (2 + 2 + 1), not once per job.
  const std::vector<JobCost> jobs = {{0, 0.0, 5.0}, {1, 0.0, 2.0, 1.0}, {2, 0.0, 2.0, 1.0}};
  const ShardSplit split = splitShards(jobs, 2);
  EXPECT_EQ(split.shardOf[1], split.shardOf[2]);
  EXPECT_NE(split.shardOf[0], split.shardOf[1]);
  EXPECT_DOUBLE_EQ(split.shardSeconds[split.shardOf[0]], 5.0);
  EXPECT_DOUBLE_EQ(split.shardSeconds[split.shardOf[1]], 5.0);
}

TEST(BatchShards, OneShardTotalsEverythingItPays) {
  const std::vector<JobCost> jobs = {{0, 2.0, 1.0}, {0, 2.0, 1.0, 0.5}, {1, 1.0, 3.0, 0.5}};
  const ShardSplit split = splitShards(jobs, 1);
  EXPECT_DOUBLE_EQ(split.shardSeconds[0], 2.0 + 1.0 + 1.0 + 1.0 + 3.0 + 0.5);
}

TEST(BatchShards, EachShardsJobsAddUpToItsTotal) {
  std::vector<JobCost> jobs;
  for (size_t j = 0; j < 40; ++j) jobs.push_back({0, 2.0, 1.0, 0.3});
  for (size_t j = 1; j < 6; ++j) jobs.push_back({j, 0.5, 2.0 * double(j), j % 2 ? 0.3 : 0.0});
  const ShardSplit split = splitShards(jobs, 4);
  std::vector<double> sum(4, 0.0);
  for (size_t j = 0; j < jobs.size(); ++j) sum[split.shardOf[j]] += split.jobSeconds[j];
  for (size_t s = 0; s < 4; ++s) EXPECT_NEAR(sum[s], split.shardSeconds[s], 1e-9) << "shard " << s;
}

TEST(BatchShards, SlashShardsAreOneBased) {
  EXPECT_EQ(parseShard("2/4"), (std::pair<size_t, size_t>{1, 4}));
  EXPECT_EQ(shardFromSlash("2/4").label, "shard 2/4");
  for (const char* bad : {"0/4", "5/4", "1/4x", "1/0", ""}) EXPECT_THROW(parseShard(bad), InputError) << bad;
}

TEST(BatchShards, SchedulerIndicesAreZeroBasedAndReadFromTheEnvironment) {
  for (const char* name : kShardIndexVariables) unsetenv(name);
  EXPECT_EQ(shardFromIndex("0", 4).index, 0u);
  EXPECT_EQ(shardFromIndex("3", 4).label, "shard 4/4");
  try {
    shardFromIndex("env", 4);
    ADD_FAILURE() << "no variable set, yet accepted";
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find("SLURM_ARRAY_TASK_ID"), std::string::npos) << e.what();
  }
  setenv("JOB_COMPLETION_INDEX", "2", 1);
  EXPECT_EQ(shardFromIndex("env", 4).index, 2u);
  setenv("SLURM_ARRAY_TASK_ID", "0", 1);  // Slurm's is read first
  const ShardChoice slurm = shardFromIndex("env", 4);
  EXPECT_EQ(slurm.index, 0u);
  EXPECT_EQ(slurm.label, "shard 1/4 (SLURM_ARRAY_TASK_ID=0)");
  setenv("SLURM_ARRAY_TASK_ID", "4", 1);
  try {
    shardFromIndex("env", 4);
    ADD_FAILURE() << "index 4 of 4 accepted";
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find("SLURM_ARRAY_TASK_ID=4"), std::string::npos) << e.what();
  }
  setenv("SLURM_ARRAY_TASK_ID", "x1", 1);
  EXPECT_THROW(shardFromIndex("env", 4), InputError);
  for (const char* name : kShardIndexVariables) unsetenv(name);
  EXPECT_THROW(shardFromIndex("4", 4), InputError);
  EXPECT_THROW(shardFromIndex("-1", 4), InputError);
  EXPECT_THROW(shardFromIndex("0", 0), InputError);
}

TEST(BatchShards, AShardFileNamesEveryJobOnceAndPlacesAppendedJobsAlike) {
  ShardFile file;
  file.shards = {{{"a", 4.0}, {"b", 1.0}}, {{"c", 3.0}}};
  file.seconds = {5.0, 3.0};
  // Written and read back, the split is the same.
  testing::ScratchDir dir;
  const ShardFile read = readShardFile(dir.write("shards.json", shardFileText(file)).string());
  ASSERT_EQ(read.shards.size(), 2u);
  EXPECT_EQ(read.shards[0][1].name, "b");
  EXPECT_DOUBLE_EQ(read.seconds[1], 3.0);
  // A job named twice, or a file of another kind, is refused naming the JSON path.
  try {
    readShardFile(dir.write("twice.json", R"({"format": "penumbra-shards", "version": 1, "shards": [
      {"jobs": [{"name": "a"}]}, {"jobs": [{"name": "a"}]}]})").string());
    ADD_FAILURE() << "a job in two shards accepted";
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find("shards[1].jobs[0].name"), std::string::npos) << e.what();
  }
  EXPECT_THROW(readShardFile(dir.write("jobs.json", R"({"jobs": []})").string()), InputError);
  const std::vector<std::string> jobs = {"a", "b", "c", "d", "e"};
  // d and e are new: each goes to the lighter shard, counting the file's mean job (8/3 s).
  EXPECT_EQ(jobsOfShardFile(file, jobs, 0, nullptr), (std::vector<size_t>{0, 1, 4}));
  size_t unplaced = 0;
  EXPECT_EQ(jobsOfShardFile(file, jobs, 1, &unplaced), (std::vector<size_t>{2, 3}));
  EXPECT_EQ(unplaced, 2u);
}

}  // namespace
}  // namespace penumbra
