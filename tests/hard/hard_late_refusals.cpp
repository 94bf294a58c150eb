// Refusals that must come before any work, and the same in every command: a shard
// checks the whole jobs file as the unsharded batch does, batch takes the budgets
// render takes, a budget that may run long says its bound before the first photon,
// an input path too long for the system is not called missing, and a sweep's wrong
// --reference leaves no folder behind.
#include "hard/hard_cli.h"
#include "plan/job_admission.h"
#include "plan/render_session.h"
#include <gtest/gtest.h>
#include <fcntl.h>
#include <sys/stat.h>
#include <unistd.h>
#include <climits>
#include <cstdlib>
#include <cstring>

namespace penumbra {
namespace {

using namespace hard;

std::string at(const ScratchDir& dir, const std::string& name) { return quote((dir / name).string()); }

void expectOneLineRefusal(const CliResult& r, const std::string& part, const std::string& what) {
  EXPECT_EQ(r.exitCode, 2) << what << "\n" << r.err;
  EXPECT_NE(r.err.find(part), std::string::npos) << what << "\n" << r.err;
  EXPECT_EQ(r.err.find("internal error"), std::string::npos) << what << "\n" << r.err;
}

TEST(HardLateRefusals, EveryShardRefusesTwoJobsWritingOneImage) {
  ScratchDir dir;
  dir.write("scene.json", kFloorScene);
  dir.write("jobs.json", R"({"jobs": [{"name": "a", "scene": "scene.json", "output": "same.png"},
    {"name": "b", "scene": "scene.json", "set": ["camera.spp=2"], "output": "same.png"}]})");
  for (const char* shard : {"1/2", "2/2"}) {
    const CliResult r = runCli("batch " + at(dir, "jobs.json") + " -q --shard " + shard);
    expectOneLineRefusal(r, "both write", std::string("--shard ") + shard);
    EXPECT_FALSE(fs::exists(dir / "same.png")) << shard;
  }
  const CliResult listed = runCli("batch " + at(dir, "jobs.json") + " -q --list-shard 1/2");
  expectOneLineRefusal(listed, "both write", "--list-shard 1/2");
}

TEST(HardLateRefusals, EveryShardRefusesAJobWritingWhatAnotherShardsJobReads) {
  ScratchDir dir;
  dir.write("scene.json", kFloorScene);
  // Job b reads its material library under a name job a writes as its image.
  dir.write("floor.obj", "mtllib floor.mtl.png\nv -1 0 1\nv 1 0 1\nv 1 0 -1\nv -1 0 -1\nusemtl red\nf 1 2 3 4\n");
  dir.write("floor.mtl.png", "newmtl red\nKd 0.8 0.1 0.1\n");
  dir.write("obj.json", R"({"camera": {"position": [0, 3, 3], "look_at": [0, 0, 0], "width": 16, "height": 12},
  "lights": [{"type": "point", "position": [0, 2, 0], "intensity": 5}],
  "objects": [{"type": "mesh", "file": "floor.obj"}], "photons": {"shadow": 0, "indirect": 0}})");
  dir.write("jobs.json", R"({"jobs": [{"name": "a", "scene": "scene.json", "output": "floor.mtl.png"},
    {"name": "b", "scene": "obj.json", "output": "b.png"}]})");
  const std::string mtl = testing::readFile(dir / "floor.mtl.png");
  for (const char* shard : {"1/2", "2/2"}) {
    const CliResult r = runCli("batch " + at(dir, "jobs.json") + " -q --shard " + shard);
    expectOneLineRefusal(r, "which job 'b' reads", std::string("--shard ") + shard);
    EXPECT_EQ(testing::readFile(dir / "floor.mtl.png"), mtl) << shard;
    EXPECT_FALSE(fs::exists(dir / "b.png")) << shard;
  }
}

TEST(HardLateRefusals, ShardsOfAGoodFileRenderEachJobOnce) {
  ScratchDir dir;
  dir.write("scene.json", kFloorScene);
  dir.write("jobs.json", R"({"jobs": [{"name": "a", "scene": "scene.json", "output": "a.png"},
    {"name": "b", "scene": "scene.json", "set": ["camera.spp=2"], "output": "b.png"},
    {"name": "c", "scene": "scene.json", "set": ["camera.spp=3"], "output": "c.png"}]})");
  std::string listed;
  for (const char* shard : {"1/2", "2/2"}) {
    listed += runCli("batch " + at(dir, "jobs.json") + " -q --list-shard " + shard).out;
    const CliResult r = runCli("batch " + at(dir, "jobs.json") + " -q --shard " + shard);
    EXPECT_EQ(r.exitCode, 0) << r.err;
  }
  for (const char* name : {"a\t", "b\t", "c\t"}) EXPECT_EQ(occurrences(listed, name), 1u) << listed;
  for (const char* image : {"a.png", "b.png", "c.png"}) EXPECT_TRUE(fs::exists(dir / image)) << image;
}

// With --keep-going a job refused on one machine (here: its output folder is missing)
// must not move other jobs between shards, or two machines would cut the file apart
// differently and render some jobs twice and others never.
TEST(HardLateRefusals, AShardSplitDoesNotDependOnWhatThisMachineRefuses) {
  ScratchDir dir;
  dir.write("scene.json", kFloorScene);
  dir.write("jobs.json", R"({"jobs": [{"name": "a", "scene": "scene.json", "output": "a.png"},
    {"name": "b", "scene": "scene.json", "set": ["camera.spp=8"], "output": "sub/b.png"},
    {"name": "c", "scene": "scene.json", "output": "c.png", "set": ["camera.spp=2"]},
    {"name": "d", "scene": "scene.json", "output": "d.png", "set": ["camera.spp=3"]}]})");
  auto split = [&] {
    return runCli("batch " + at(dir, "jobs.json") + " -q --keep-going --list-shard 1/2").out + "|" +
           runCli("batch " + at(dir, "jobs.json") + " -q --keep-going --list-shard 2/2").out;
  };
  const std::string refused = split();
  fs::create_directory(dir / "sub");
  EXPECT_EQ(split(), refused);
}

TEST(HardLateRefusals, BatchRefusesEveryBudgetRenderRefuses) {
  ScratchDir dir;
  dir.write("scene.json", kFloorScene);
  dir.write("jobs.json", R"({"jobs": [{"name": "a", "scene": "scene.json", "output": "a.png"}]})");
  const std::pair<const char*, const char*> budgets[] = {
      {"--time-limit -1", "--time-limit"}, {"--time-limit nan", "--time-limit"}, {"--time-limit ''", "--time-limit"},
      {"--target-error -1", "--target-error"}, {"--target-error nan", "--target-error"},
      {"--target-error ''", "--target-error"}, {"--time-limit inf", "--time-limit"}};
  for (const auto& [budget, option] : budgets) {
    const std::string commands[] = {"batch " + at(dir, "jobs.json") + " -q ",
                                    "render " + at(dir, "scene.json") + " -q -o " + at(dir, "r.png") + " ",
                                    "sweep " + at(dir, "scene.json") + " -q -o " + at(dir, "sweep") + " --spp 1,2 "};
    for (const std::string& command : commands) {
      const CliResult r = runCli(command + budget);
      expectOneLineRefusal(r, option, command + budget);
    }
    EXPECT_FALSE(fs::exists(dir / "a.png")) << budget;
    EXPECT_FALSE(fs::exists(dir / "r.png")) << budget;
    EXPECT_FALSE(fs::exists(dir / "sweep")) << budget;
  }
}

// The note comes from the session's own prepare step, the one every command runs
// before the first photon: nothing here renders.
std::vector<std::string> notesOfPreparing(const std::string& scene, const RenderBudget& budget) {
  std::vector<std::string> notes;
  SessionOptions options;
  options.threads = 2;
  options.notice = [&](const std::string& n) { notes.push_back(n); };
  RenderSession session(options);
  JobRequest request;
  request.scenePath = scene;
  request.budget = budget;
  PlannedJob job = session.plan(request);
  session.prepare(job);
  return notes;
}

TEST(HardLateRefusals, ABudgetThatMayRunLongSaysItsBoundBeforeItStarts) {
  ScratchDir dir;
  dir.write("scene.json", kFloorScene);
  const std::string scene = (dir / "scene.json").string();
  EXPECT_TRUE(notesOfPreparing(scene, {}).empty()) << "an unbudgeted tiny render is not long";

  RenderBudget tinyError;
  tinyError.targetError = 1e-30;
  const std::vector<std::string> error = notesOfPreparing(scene, tinyError);
  ASSERT_EQ(error.size(), 1u);
  EXPECT_NE(error[0].find("--target-error 1e-30 (lighting) may run up to"), std::string::npos) << error[0];
  EXPECT_NE(error[0].find("100000 passes"), std::string::npos) << error[0];

  RenderBudget hugeTime;
  hugeTime.seconds = 1e308;
  const std::vector<std::string> time = notesOfPreparing(scene, hugeTime);
  ASSERT_EQ(time.size(), 1u);
  EXPECT_NE(time[0].find("--time-limit 1e+308 s may run up to"), std::string::npos) << time[0];

  RenderBudget shortTime;
  shortTime.seconds = 5.0;
  EXPECT_TRUE(notesOfPreparing(scene, shortTime).empty()) << "a 5 s limit stays under the long-job threshold";
}

TEST(HardLateRefusals, BudgetBoundIsTheTimeLimitOrThePassLimit) {
  ResourceEstimate e;
  e.plan.passes = 4;
  e.photonSeconds = 2.0;
  e.renderSeconds = 2.5;
  e.bvhSeconds = 0.5;  // one pass: (4.5 - 0.5) / 4 = 1 s
  RenderBudget b;
  EXPECT_EQ(budgetBoundSeconds(b, e), 0.0);
  b.targetError = 0.01;
  EXPECT_DOUBLE_EQ(budgetBoundSeconds(b, e), 0.5 + kBudgetMaxPasses * 1.0);
  b.seconds = 100.0;
  EXPECT_DOUBLE_EQ(budgetBoundSeconds(b, e), 100.0 * (1.0 + kTimeLimitOverrun));
  b.seconds = 0.1;  // two passes always run
  EXPECT_DOUBLE_EQ(budgetBoundSeconds(b, e), 0.5 + 2.0);
}

// A scene file at the end of a path longer than PATH_MAX: it exists (made one folder
// at a time with *at calls), but no path-taking call can reach it.
TEST(HardLateRefusals, AnInputPathLongerThanPathMaxIsNotCalledMissing) {
  ScratchDir dir;
  const std::string name(200, 'd');
  // ScratchDir's remove_all goes by path; rm walks a tree deeper than PATH_MAX.
  struct RemoveDeep {
    std::string top;
    ~RemoveDeep() { (void)std::system(("rm -rf " + quote(top)).c_str()); }
  } removeDeep{(dir / name).string()};
  int fd = ::open(dir.path().c_str(), O_RDONLY | O_DIRECTORY);
  ASSERT_GE(fd, 0);
  std::string path = dir.path().string();
  while (path.size() <= PATH_MAX) {
    ASSERT_EQ(::mkdirat(fd, name.c_str(), 0755), 0);
    const int next = ::openat(fd, name.c_str(), O_RDONLY | O_DIRECTORY);
    ::close(fd);
    ASSERT_GE(next, 0);
    fd = next;
    path += "/" + name;
  }
  const int file = ::openat(fd, "scene.json", O_WRONLY | O_CREAT, 0644);
  ASSERT_GE(file, 0);
  ASSERT_EQ(::write(file, kFloorScene, std::strlen(kFloorScene)), static_cast<ssize_t>(std::strlen(kFloorScene)));
  ::close(file);
  ::close(fd);
  path += "/scene.json";
  const CliResult r = runCli("check " + quote(path));
  expectOneLineRefusal(r, "longer than the system allows (PATH_MAX", "check");
  EXPECT_EQ(r.err.find("does not exist"), std::string::npos) << r.err;
}

TEST(HardLateRefusals, SweepRefusesAReferenceOfAnotherSizeNamingBothFilesAndLeavesNoFolder) {
  ScratchDir dir;
  dir.write("scene.json", kFloorScene);
  dir.write("small.json", std::string(kFloorScene).replace(std::string(kFloorScene).find("\"width\": 16"), 11,
                                                            "\"width\": 8"));
  ASSERT_EQ(runCli("render " + at(dir, "small.json") + " -q -o " + at(dir, "ref.exr")).exitCode, 0);
  const CliResult r = runCli("sweep " + at(dir, "scene.json") + " -q -o " + at(dir, "sweep") + " --spp 1,2 --reference " +
                             at(dir, "ref.exr"));
  expectOneLineRefusal(r, "8x12", "sweep");
  EXPECT_NE(r.err.find((dir / "ref.exr").string()), std::string::npos) << r.err;
  EXPECT_NE(r.err.find((dir / "scene.json").string()), std::string::npos) << r.err;
  EXPECT_NE(r.err.find("16x12"), std::string::npos) << r.err;
  EXPECT_FALSE(fs::exists(dir / "sweep")) << "the refused sweep made its folder";
}

}  // namespace
}  // namespace penumbra
