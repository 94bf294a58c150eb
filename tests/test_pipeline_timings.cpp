// CPU time where the user reads times: --stats and the render summary, sweep rows,
// batch jobs, and `penumbra bench` (its table, its JSON with the thread counts
// interleaved, and its refusals of bad input before any render). Values are
// checked for sanity (a share in (0, cores]), never for speed.
#include "plan/batch/batch_run.h"
#include "support/cli_run.h"
#include <gtest/gtest.h>
#include <nlohmann/json.hpp>
#include <tbb/info.h>
#include <algorithm>
#include <filesystem>
#include <sstream>

namespace penumbra {
namespace {

namespace fs = std::filesystem;
using testing::quote;
using testing::runCli;
using testing::ScratchDir;
const std::string kScene = std::string(PENUMBRA_SOURCE_DIR) + "/scenes/fig02_phong.json";
const std::string kSmall = " --set camera.width=40 --set camera.height=30";

// The CPU seconds are the whole process's: beside the one worker, the image writer
// and the progress ticker run, so a short span at one thread may pass a share of 1.
// No process holds more than the machine's cores: a share above that is a wrong span.
void expectSaneShare(double cpu, double share, const std::string& what) {
  EXPECT_GT(cpu, 0.0) << what;
  EXPECT_GT(share, 0.0) << what;
  EXPECT_LE(share, double(tbb::info::default_concurrency()) + 0.05) << what;
}

TEST(Timings, StatsAndSummaryCarryCpuSecondsShareAndLoad) {
  const ScratchDir dir;
  const auto r = runCli("render " + quote(kScene) + " -o " + quote((dir / "a.png").string()) + " -t 1" + kSmall +
                        " --stats " + quote((dir / "s.json").string()));
  ASSERT_EQ(r.exitCode, 0) << r.err;
  const nlohmann::json s = nlohmann::json::parse(testing::readFile(dir / "s.json"));
  ASSERT_TRUE(s.contains("cpu_s") && s.contains("cpu_share") && s.contains("load_avg_1m")) << s.dump();
  expectSaneShare(s["cpu_s"].get<double>(), s["cpu_share"].get<double>(), "--stats");
  EXPECT_NEAR(s["cpu_share"].get<double>(), s["cpu_s"].get<double>() / s["time_s"]["total"].get<double>(), 1e-9)
      << "one thread: the share is CPU over the total's wall time";
  EXPECT_TRUE(s["load_avg_1m"].is_number()) << s["load_avg_1m"];
  EXPECT_NE(r.err.find("  cpu "), std::string::npos) << r.err;
  EXPECT_NE(r.err.find(" (user + sys), share "), std::string::npos) << r.err;
  EXPECT_NE(r.err.find(" of 1 thread, load "), std::string::npos) << r.err;
}

TEST(Timings, SweepRowsCarryCpuColumns) {
  const ScratchDir dir;
  const auto r = runCli("sweep " + quote(kScene) + " -o " + quote((dir / "sw").string()) + " -q -t 1 --spp 1,2" + kSmall);
  ASSERT_EQ(r.exitCode, 0) << r.err;
  std::istringstream csv(testing::readFile(dir / "sw" / "results.csv"));
  std::string line;
  std::vector<std::vector<std::string>> rows;
  while (std::getline(csv, line)) {
    std::vector<std::string> cells;
    std::istringstream in(line);
    for (std::string c; std::getline(in, c, ',');) cells.push_back(c);
    rows.push_back(cells);
  }
  ASSERT_EQ(rows.size(), 3u);
  const auto column = [&](const std::string& name) {
    return size_t(std::find(rows[0].begin(), rows[0].end(), name) - rows[0].begin());
  };
  const size_t cpu = column("cpu_s"), share = column("cpu_share"), load = column("load_avg_1m");
  ASSERT_LT(load, rows[0].size()) << line;
  for (size_t i = 1; i < rows.size(); ++i) {
    expectSaneShare(std::stod(rows[i][cpu]), std::stod(rows[i][share]), "row " + rows[i][0]);
    EXPECT_GE(std::stod(rows[i][load]), 0.0);
  }
  EXPECT_NE(testing::readFile(dir / "sw" / "report.md").find("Sweep cpu "), std::string::npos);
}

TEST(Timings, BatchJobsAndTheWholeBatchCarryCpuTime) {
  const ScratchDir dir;
  BatchRequest req;
  req.session.threads = 1;
  for (int i = 0; i < 2; ++i) {
    const std::string out = (dir / ("j" + std::to_string(i) + ".png")).string();
    req.jobs.push_back({"j" + std::to_string(i), kScene, {"camera.width=40", "camera.height=30"}, {{"", out}}, "-", {}, std::nullopt});
  }
  const BatchOutcome out = runBatch(req);
  ASSERT_EQ(out.rendered, 2u);
  for (const BatchJobResult& j : out.jobs) {
    expectSaneShare(j.cpu.cpuSeconds, j.cpu.share, j.name);
    EXPECT_DOUBLE_EQ(j.cpu.wallSeconds, j.seconds);
  }
  expectSaneShare(out.cpu.cpuSeconds, out.cpu.share, "batch");
  EXPECT_DOUBLE_EQ(out.cpu.wallSeconds, out.seconds);
  const auto cli = runCli("batch " + quote(kScene) + " -o " + quote((dir / "b").string()) + " -t 1" + kSmall);
  ASSERT_EQ(cli.exitCode, 0) << cli.err;
  EXPECT_NE(cli.err.find("     cpu share  reused"), std::string::npos) << cli.err;
  EXPECT_NE(cli.err.find(" s; cpu "), std::string::npos) << cli.err;
}

// Two rounds at 1 and 2 threads: renders and control passes alternate 1, 2, 1, 2.
TEST(Bench, PrintsSpeedupBesideTheControlAndWritesEverySample) {
  if (tbb::info::default_concurrency() < 2) GTEST_SKIP() << "needs two cores";
  const ScratchDir dir;
  const fs::path json = dir / "bench.json";
  const auto r = runCli("bench " + quote(kScene) + " --threads 1,2 --repeat 2 -q" + kSmall + " --json " +
                        quote(json.string()));
  ASSERT_EQ(r.exitCode, 0) << r.err;
  EXPECT_NE(r.out.find("threads 1,2 interleaved, 2 rounds"), std::string::npos) << r.out;
  EXPECT_NE(r.out.find("speed-up 2/1 of the total: "), std::string::npos) << r.out;
  EXPECT_NE(r.out.find(", beside the control's "), std::string::npos) << r.out;
  EXPECT_NE(r.out.find("\ncontrol "), std::string::npos) << r.out;
  EXPECT_NE(r.out.find("\ncpu share "), std::string::npos) << r.out;
  const nlohmann::json j = nlohmann::json::parse(testing::readFile(json));
  const nlohmann::json& runs = j["scenes"][0]["runs"];
  ASSERT_EQ(runs.size(), 4u);
  ASSERT_EQ(j["control"]["runs"].size(), 4u);
  for (size_t i = 0; i < 4; ++i) {
    EXPECT_EQ(runs[i]["threads"], i % 2 + 1);
    EXPECT_EQ(runs[i]["round"], i / 2);
    EXPECT_EQ(j["control"]["runs"][i]["threads"], i % 2 + 1);
    expectSaneShare(runs[i]["cpu_s"], runs[i]["cpu_share"], "run " + std::to_string(i));
    EXPECT_GT(runs[i]["time_s"]["render"].get<double>(), 0.0);
  }
  const nlohmann::json& total = j["scenes"][0]["stages_s"]["total"];
  EXPECT_LE(total["1"]["min"].get<double>(), total["1"]["median"].get<double>());
  EXPECT_GT(total["speedup"]["2/1"]["min"].get<double>(), 0.0);
  EXPECT_GT(j["control"]["seconds"]["speedup"]["2/1"]["min"].get<double>(), 0.0);
}

// Bad input: one line, exit 2, nothing rendered (no progress line) and no JSON.
TEST(Bench, RefusesBadInputBeforeAnyRender) {
  const ScratchDir dir;
  const std::string json = quote((dir / "b.json").string());
  const std::string scene = quote(kScene);
  const std::pair<std::string, std::string> cases[] = {
      {scene + " " + quote((dir / "missing.json").string()), "missing.json"},
      {scene + " --threads 1,x", "--threads: expected thread counts like 1,2"},
      {scene + " --threads 0", "--threads: expected thread counts like 1,2"},
      {scene + " --threads 1,1", "--threads: 1 is given twice"},
      {scene + " --threads 100000", "--threads: 100000 is more than the"},
      {scene + " --repeat 0", "--repeat: expected a count of rounds, at least 1, got 0"},
      {"- --repeat 1", "a scene on stdin can be read only once"},
  };
  for (const auto& [args, says] : cases) {
    const auto r = runCli("bench " + args + " --json " + json);
    EXPECT_EQ(r.exitCode, 2) << args << "\n" << r.err;
    EXPECT_NE(r.err.find(says), std::string::npos) << args << "\n" << r.err;
    EXPECT_EQ(std::count(r.err.begin(), r.err.end(), '\n'), 1) << args << "\n" << r.err;
    EXPECT_FALSE(fs::exists(dir / "b.json")) << args;
  }
  const auto intoScene = runCli("bench " + scene + " --json " + scene);
  EXPECT_EQ(intoScene.exitCode, 2) << intoScene.err;
  EXPECT_NE(intoScene.err.find("--json"), std::string::npos) << intoScene.err;
}

}  // namespace
}  // namespace penumbra
