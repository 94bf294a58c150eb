// A batch on a farm: whether a job is up to date is decided from its outputs
// alone and per job (touching, copying or appending to the jobs file re-renders
// nothing else); --status says why, with its own exit code; shards come from a
// split planned once, named by a scheduler's 0-based index; a broken job fails
// only its shard; output folders a jobs file names are made.
#include "hard/hard_cli.h"
#include <gtest/gtest.h>
#include <nlohmann/json.hpp>
#include <cstdlib>
#include <fstream>

namespace penumbra {
namespace {

using namespace hard;

// The exit codes batch documents (cli/batch_command.h).
constexpr int kJobsFailed = 3, kNotUpToDate = 4;

std::string at(const ScratchDir& dir, const std::string& name) { return quote((dir / name).string()); }

std::string jobsText(int count, const std::string& extra = "") {
  std::string jobs;
  for (int i = 0; i < count; ++i) {
    jobs += (i ? ",\n" : "") + std::string(R"({"name": "j)") + std::to_string(i) +
            R"(", "scene": "scene.json", "set": ["camera.spp=)" + std::to_string(i + 1) + R"("], "output": "out/j)" +
            std::to_string(i) + R"(.png"})";
  }
  return "{\"jobs\": [" + jobs + extra + "]}";
}

nlohmann::json stats(const CliResult& r) {
  EXPECT_EQ(r.exitCode, 0) << r.err;
  return nlohmann::json::parse(r.out.substr(r.out.find('{')), nullptr, false);
}

TEST(HardBatchFarm, UpToDateIsDecidedPerJobWithoutLoadingAScene) {
  ScratchDir dir;
  dir.write("scene.json", kFloorScene);
  dir.write("jobs.json", jobsText(3));
  const std::string batch = "batch " + at(dir, "jobs.json") + " -q --stats - ";
  EXPECT_EQ(stats(runCli(batch))["jobs"]["rendered"], 3);  // out/ did not exist: made
  // Touched, or copied without its time: nothing changed, nothing renders, no scene is read.
  std::ofstream(dir / "jobs.json", std::ios::app) << "\n";
  nlohmann::json again = stats(runCli(batch));
  EXPECT_EQ(again["jobs"]["up_to_date"], 3);
  EXPECT_EQ(again["scene_files_read"], 0);
  fs::copy_file(dir / "jobs.json", dir / "copy.json");
  EXPECT_EQ(stats(runCli("batch " + at(dir, "copy.json") + " -q --stats -"))["jobs"]["up_to_date"], 3);
  // Appending a job renders that job alone; --status says which is missing first.
  dir.write("jobs.json", jobsText(3, R"(, {"name": "new", "scene": "scene.json", "output": "out/new.png"})"));
  const CliResult status = runCli("batch " + at(dir, "jobs.json") + " --status");
  EXPECT_EQ(status.exitCode, kNotUpToDate) << status.err;
  EXPECT_EQ(occurrences(status.out, "missing: "), 1u) << status.out;
  EXPECT_NE(status.out.find("4 jobs: 3 up to date, 1 missing"), std::string::npos) << status.out;
  EXPECT_EQ(stats(runCli(batch))["jobs"]["rendered"], 1);
  EXPECT_EQ(runCli("batch " + at(dir, "jobs.json") + " --status").exitCode, 0);
  // An edited scene makes every job that read it stale, and says so.
  dir.write("scene.json", std::string(kFloorScene) + " ");
  const CliResult stale = runCli("batch " + at(dir, "jobs.json") + " --status");
  EXPECT_EQ(stale.exitCode, kNotUpToDate);
  EXPECT_EQ(occurrences(stale.out, "scene.json changed"), 4u) << stale.out;
}

TEST(HardBatchFarm, ARerunOfAnUpToDateOrbitReadsNoScene) {
  ScratchDir dir;
  dir.write("scene.json", kFloorScene);
  dir.write("jobs.json", R"({"jobs": [{"scene": "scene.json", "output": "out/t_{i:02}.png",
    "orbit": {"count": 64, "radius": 4, "height": 2}}]})");
  const std::string batch = "batch " + at(dir, "jobs.json") + " -q --stats - ";
  const nlohmann::json first = stats(runCli(batch));
  EXPECT_EQ(first["jobs"]["rendered"], 64);
  EXPECT_EQ(first["scene_files_read"], 1);  // 64 frames, one scene file read
  const nlohmann::json again = stats(runCli(batch));
  EXPECT_EQ(again["jobs"]["up_to_date"], 64);
  EXPECT_EQ(again["scene_files_read"], 0);
  EXPECT_EQ(again["scenes_built"], 0);
}

TEST(HardBatchFarm, AnOrbitIsPlannedIntoShardsReadingItsSceneOnce) {
  ScratchDir dir;
  dir.write("scene.json", kFloorScene);
  dir.write("jobs.json", R"({"jobs": [{"scene": "scene.json", "output": "out/t_{i:03}.png",
    "orbit": {"count": 200, "radius": 4, "height": 2}}]})");
  const CliResult r = runCli("batch " + at(dir, "jobs.json") + " -q --plan-shards 4 -o " + at(dir, "shards.json") +
                             " --stats -");
  EXPECT_EQ(stats(r)["scene_files_read"], 1);
  std::ifstream in(dir / "shards.json");
  const nlohmann::json split = nlohmann::json::parse(in, nullptr, false);
  ASSERT_TRUE(split.is_object()) << r.err;
  size_t jobs = 0;
  for (const auto& shard : split["shards"]) jobs += shard["jobs"].size();
  EXPECT_EQ(jobs, 200u);
  EXPECT_FALSE(fs::exists(dir / "out")) << "planning renders nothing";
}

TEST(HardBatchFarm, ShardsFromAPlannedSplitRenderEveryJobOnceAndABrokenJobFailsOnlyItsShard) {
  ScratchDir dir;
  dir.write("scene.json", kFloorScene);
  dir.write("jobs.json", jobsText(5, R"(, {"name": "broken", "scene": "missing.json", "output": "out/b.png"})"));
  const std::string jobs = at(dir, "jobs.json");
  // The submit host refuses a broken file, unless told to go on.
  EXPECT_EQ(runCli("batch " + jobs + " -q --plan-shards 2 -o " + at(dir, "shards.json")).exitCode, 2);
  ASSERT_EQ(runCli("batch " + jobs + " -q --keep-going --plan-shards 2 -o " + at(dir, "shards.json")).exitCode, 0);
  std::string listed;
  int failedShards = 0;
  for (int index = 0; index < 2; ++index) {
    const std::string shard = " --shard-file " + at(dir, "shards.json") + " --shard-index " + std::to_string(index) +
                              " --shard-count 2";
    listed += runCli("batch " + jobs + " -q --list-shard" + shard).out;
    const CliResult r = runCli("batch " + jobs + " -q --keep-going" + shard);
    if (r.exitCode == kJobsFailed) ++failedShards;
    else EXPECT_EQ(r.exitCode, 0) << r.err;
  }
  EXPECT_EQ(failedShards, 1);
  for (int i = 0; i < 5; ++i) {
    EXPECT_EQ(occurrences(listed, "j" + std::to_string(i) + "\t"), 1u) << listed;
    EXPECT_TRUE(fs::exists(dir / "out" / ("j" + std::to_string(i) + ".png"))) << i;
  }
  EXPECT_EQ(occurrences(listed, "# shard 1/2: "), 2u) << listed;  // each listing ends with every shard's total
}

TEST(HardBatchFarm, TheSchedulersIndexIsZeroBasedAndAMissingOneIsRefused) {
  ScratchDir dir;
  dir.write("scene.json", kFloorScene);
  dir.write("jobs.json", jobsText(4));
  const std::string batch = "batch " + at(dir, "jobs.json") + " -q ";
  const CliResult noVar = runCli(batch + "--shard-index env --shard-count 4");
  if (!std::getenv("SLURM_ARRAY_TASK_ID") && !std::getenv("JOB_COMPLETION_INDEX") &&
      !std::getenv("AWS_BATCH_JOB_ARRAY_INDEX")) {
    EXPECT_EQ(noVar.exitCode, 2);
    EXPECT_NE(noVar.err.find("SLURM_ARRAY_TASK_ID"), std::string::npos) << noVar.err;
  }
  const CliResult tooLarge = runCli(batch + "--shard-index 4 --shard-count 4");
  EXPECT_EQ(tooLarge.exitCode, 2);
  EXPECT_NE(tooLarge.err.find("0..3"), std::string::npos) << tooLarge.err;
  EXPECT_EQ(runCli(batch + "--shard-index 1").exitCode, 2);  // no count: never taken from the environment
  // Index 0 of 4 is the first shard: the same jobs as --shard 1/4.
  EXPECT_EQ(runCli(batch + "--list-shard --shard-index 0 --shard-count 4").out, runCli(batch + "--list-shard 1/4").out);
}

}  // namespace
}  // namespace penumbra
