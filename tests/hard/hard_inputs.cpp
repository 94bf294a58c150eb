// No input is ever overwritten or read stale: outputs against every file a render
// reads (OBJ's MTL, textures), batch jobs against each other, the up-to-date check
// against side files, and sweep resume against a folder of another sweep.
#include "hard/hard_cli.h"
#include <gtest/gtest.h>
#include <chrono>

namespace penumbra {
namespace {

using namespace hard;

// The same floor as an OBJ whose MTL gives its colour.
void writeObjScene(const ScratchDir& dir) {
  dir.write("floor.obj", "mtllib floor.mtl\nv -1 0 1\nv 1 0 1\nv 1 0 -1\nv -1 0 -1\nusemtl red\nf 1 2 3 4\n");
  dir.write("floor.mtl", "newmtl red\nKd 0.8 0.1 0.1\n");
  dir.write("obj.json", R"({"camera": {"position": [0, 3, 3], "look_at": [0, 0, 0], "width": 16, "height": 12},
  "lights": [{"type": "point", "position": [0, 2, 0], "intensity": 5}],
  "objects": [{"type": "mesh", "file": "floor.obj"}], "photons": {"shadow": 0, "indirect": 0}})");
}

std::string at(const ScratchDir& dir, const std::string& name) { return quote((dir / name).string()); }

TEST(HardInputs, StatsNeverOverwriteAnObjsMaterialLibrary) {
  ScratchDir dir;
  writeObjScene(dir);
  const std::string mtl = testing::readFile(dir / "floor.mtl");
  const CliResult r = runCli("render " + at(dir, "obj.json") + " -q -o " + at(dir, "a.png") + " --stats " +
                             at(dir, "floor.mtl"));
  EXPECT_EQ(r.exitCode, 2) << r.err;
  EXPECT_NE(r.err.find("is an input of this render"), std::string::npos) << r.err;
  EXPECT_EQ(testing::readFile(dir / "floor.mtl"), mtl);
}

TEST(HardInputs, BatchRefusesTwoJobsWritingOneImageBeforeRendering) {
  ScratchDir dir;
  dir.write("scene.json", kFloorScene);
  dir.write("jobs.json", R"({"jobs": [{"name": "a", "scene": "scene.json", "output": "out.png"},
    {"name": "b", "scene": "scene.json", "set": ["camera.spp=2"], "output": "out.png"}]})");
  const CliResult r = runCli("batch " + at(dir, "jobs.json") + " -q");
  EXPECT_EQ(r.exitCode, 2) << r.err;
  EXPECT_NE(r.err.find("both write"), std::string::npos) << r.err;
  EXPECT_FALSE(fs::exists(dir / "out.png"));
}

TEST(HardInputs, BatchRefusesAnOrbitWritingEveryViewIntoOneFile) {
  ScratchDir dir;
  dir.write("scene.json", kFloorScene);
  dir.write("jobs.json", R"({"jobs": [{"scene": "scene.json", "output": "turn.png", "orbit": {"count": 4}}]})");
  const CliResult r = runCli("batch " + at(dir, "jobs.json") + " -q");
  EXPECT_EQ(r.exitCode, 2) << r.err;
  EXPECT_NE(r.err.find("jobs[0].output"), std::string::npos) << r.err;
  EXPECT_FALSE(fs::exists(dir / "turn.png"));
}

TEST(HardInputs, BatchRefusesAJobWritingAnotherJobsTexture) {
  ScratchDir dir;
  writeObjScene(dir);
  dir.write("scene.json", kFloorScene);
  const std::string mtl = testing::readFile(dir / "floor.mtl");
  // Job a's output is an input (the MTL) of job b, whatever order they run in.
  dir.write("jobs.json", R"({"jobs": [{"name": "a", "scene": "scene.json", "output": "floor.mtl.png"},
    {"name": "b", "scene": "obj.json", "output": "b.png"}]})");
  fs::rename(dir / "floor.mtl", dir / "floor.mtl.png");
  dir.write("floor.obj", "mtllib floor.mtl.png\nv -1 0 1\nv 1 0 1\nv 1 0 -1\nv -1 0 -1\nusemtl red\nf 1 2 3 4\n");
  const CliResult r = runCli("batch " + at(dir, "jobs.json") + " -q");
  EXPECT_EQ(r.exitCode, 2) << r.err;
  EXPECT_NE(r.err.find("which job 'b' reads"), std::string::npos) << r.err;
  EXPECT_EQ(testing::readFile(dir / "floor.mtl.png"), mtl);
}

TEST(HardInputs, BatchJobsFileMistakesAreBadInputNamingTheirPath) {
  ScratchDir dir;
  dir.write("scene.json", kFloorScene);
  const std::pair<const char*, const char*> cases[] = {
      {R"({"jobs": [{"scene": "scene.json", "output": "o.exr", "views": ["beauty", "beauty"]}]})", "jobs[0].views[1]"},
      {R"({"jobs": [{"scene": "scene.json", "output": "o_{i}.png", "orbit": {"count": 4294967301}}]})",
       "jobs[0].orbit.count"},
      {R"({"jobs": [{"scene": "scene.json", "output": "o_{i}.png", "orbit": {"count": 2, "center": ["a", 0, 0]}}]})",
       "jobs[0].orbit.center[0]"},
      {R"({"jobs": [{"scene": "scene.json", "output": "o.png", "views": ["caustic"]}]})", "needs the physical model"}};
  for (const auto& [jobs, where] : cases) {
    dir.write("jobs.json", jobs);
    const CliResult r = runCli("batch " + at(dir, "jobs.json") + " -q");
    EXPECT_EQ(r.exitCode, 2) << jobs << "\n" << r.err;
    EXPECT_NE(r.err.find(where), std::string::npos) << r.err;
    EXPECT_EQ(r.err.find("internal error"), std::string::npos) << r.err;
  }
}

TEST(HardInputs, BatchRendersAgainWhenAnObjsMaterialLibraryChanges) {
  ScratchDir dir;
  writeObjScene(dir);
  dir.write("jobs.json", R"({"jobs": [{"name": "floor", "scene": "obj.json", "output": "floor.png"}]})");
  ASSERT_EQ(runCli("batch " + at(dir, "jobs.json") + " -q").exitCode, 0);
  const CliResult again = runCli("batch " + at(dir, "jobs.json"));
  EXPECT_NE(again.err.find("1 up to date"), std::string::npos) << again.err;
  // An edit to the MTL only, dated after the image.
  dir.write("floor.mtl", "newmtl red\nKd 0.1 0.8 0.1\n");
  fs::last_write_time(dir / "floor.mtl", fs::last_write_time(dir / "floor.png") + std::chrono::seconds(2));
  const CliResult edited = runCli("batch " + at(dir, "jobs.json"));
  EXPECT_NE(edited.err.find("1 rendered"), std::string::npos) << edited.err;
}

TEST(HardInputs, SweepRefusesToResumeAnotherSweepsFolder) {
  ScratchDir dir;
  dir.write("a.json", kFloorScene);
  dir.write("b.json", kFloorScene);  // the same text: only the scene's name differs
  const std::string out = at(dir, "sweep");
  const std::string knobs = " --spp 1,2 --no-gate-compare -q -o " + out;
  ASSERT_EQ(runCli("sweep " + at(dir, "a.json") + knobs).exitCode, 0);
  struct Case {
    std::string args, says;
  };
  for (const Case& c : {Case{"sweep " + at(dir, "b.json") + knobs, "another scene"},
                        Case{"sweep " + at(dir, "a.json") + knobs + " --set camera.width=8", "another --set values"},
                        Case{"sweep " + at(dir, "a.json") + knobs + " --disable packets", "another --enable/--disable"}}) {
    const CliResult r = runCli(c.args);
    EXPECT_EQ(r.exitCode, 2) << c.args << "\n" << r.err;
    EXPECT_NE(r.err.find(c.says), std::string::npos) << r.err;
  }
  // Its own sweep resumes; --force starts another one.
  EXPECT_EQ(runCli("sweep " + at(dir, "a.json") + knobs).exitCode, 0);
  EXPECT_EQ(runCli("sweep " + at(dir, "b.json") + knobs + " --force").exitCode, 0);
}

}  // namespace
}  // namespace penumbra
