// The command line as pbrt and Mitsuba users type it: -t/--nthreads, -D, --outfile,
// a scene on stdin, `penumbra check`, a close-match suggestion for a mistyped
// option, --trace-pixel refusing an image name, and the exit codes in --help.
#include "io/image_io.h"
#include "support/cli_run.h"
#include <gtest/gtest.h>
#include <algorithm>
#include <filesystem>

namespace penumbra {
namespace {

using testing::quote;
using testing::runCli;
using testing::ScratchDir;
const std::string kScenes = std::string(PENUMBRA_SOURCE_DIR) + "/scenes/";

TEST(CliHabits, AliasesRenderTheSameImageAsTheLongOptions) {
  ScratchDir dir;
  const std::string scene = quote(kScenes + "fig02_phong.json");
  const auto a = runCli("render " + scene + " -o " + quote((dir / "a.png").string()) +
                        " --threads 2 --set camera.width=40 --set camera.height=30 -q");
  const auto b = runCli("render " + scene + " --outfile " + quote((dir / "b.png").string()) +
                        " -t 2 -D camera.width=40 -D camera.height=30 -q");
  // runCli closes stdin; the scene goes in through a pipe instead.
  const std::string cat = "cat " + scene + " | " + quote(PENUMBRA_BINARY) + " render - --outfile " +
                          quote((dir / "c.png").string()) + " --nthreads 1 -D camera.width=40 -D camera.height=30 -q";
  testing::CliResult c;
  c.exitCode = WEXITSTATUS(std::system(cat.c_str()));
  ASSERT_EQ(a.exitCode, 0) << a.err;
  ASSERT_EQ(b.exitCode, 0) << b.err;
  ASSERT_EQ(c.exitCode, 0) << c.err;
  EXPECT_EQ(testing::readFile(dir / "a.png"), testing::readFile(dir / "b.png"));
  const Image ia = readImage((dir / "a.png").string()), ic = readImage((dir / "c.png").string());
  EXPECT_EQ(ia.pixels.size(), ic.pixels.size());
  EXPECT_TRUE(ia.pixels == ic.pixels) << "stdin renders the same pixels";
}

TEST(CliHabits, MistakesGetOneLineAndExitTwo) {
  const std::string scene = quote(kScenes + "fig03_shadows.json");
  const auto typo = runCli("render " + scene + " -o x.png --thread 2");
  EXPECT_EQ(typo.exitCode, 2);
  EXPECT_NE(typo.err.find("unknown option '--thread' (did you mean \"--threads\"?)"), std::string::npos) << typo.err;
  const auto trace = runCli("render " + scene + " --trace-pixel 3,3 -o t.png");
  EXPECT_EQ(trace.exitCode, 2);
  EXPECT_NE(trace.err.find("--trace-pixel writes JSON"), std::string::npos) << trace.err;
  const auto help = runCli("--help");
  EXPECT_EQ(help.exitCode, 0);
  EXPECT_NE(help.out.find("Exit codes: 0 done; 1 internal error"), std::string::npos);
  EXPECT_NE(help.out.find("3 batch: some jobs failed"), std::string::npos) << help.out;
}

TEST(CliHabits, CheckValidatesWithoutRendering) {
  const auto ok = runCli("check " + quote(kScenes + "showcase.json") + " " + quote(kScenes + "soft_shadows.json"));
  EXPECT_EQ(ok.exitCode, 0) << ok.err;
  EXPECT_NE(ok.out.find("showcase.json: ok (classic, 3 meshes with 16260 triangles"), std::string::npos) << ok.out;
  EXPECT_NE(ok.out.find("  bounds [-6, 0, -9] .. [6, 3.2, 5] (size 12 x 3.2 x 14)"), std::string::npos) << ok.out;
  const auto bad = runCli("check " + quote(kScenes + "showcase.json") + " -D render.max_depth=-1");
  EXPECT_EQ(bad.exitCode, 2);
  EXPECT_NE(bad.err.find("render.max_depth"), std::string::npos) << bad.err;
}

}  // namespace
}  // namespace penumbra

namespace penumbra {
namespace {

// render, sweep and batch go through one render session: each refuses a job that
// cannot fit (1e9 shadow photons in the gated Cornell box) before any photon, with
// exit 2 and the same one-line estimate, and each takes --enable / --disable.
TEST(CliHabits, EveryCommandRefusesAnOversizedJobWithTheSameEstimate) {
  testing::ScratchDir dir;
  const std::string scene = testing::quote(std::string(PENUMBRA_SOURCE_DIR) + "/scenes/fig14_cornell.json");
  const std::string huge = " --set photons.shadow=1e9 --set photons.gate=on --max-memory 8G";
  const std::string jobs = dir.write("jobs.json", "{\"jobs\": [{\"scene\": \"" + std::string(PENUMBRA_SOURCE_DIR) +
                                                      "/scenes/fig14_cornell.json\", \"output\": \"out.png\"}]}")
                               .string();
  const testing::CliResult render =
      testing::runCli("render " + scene + " -o " + testing::quote((dir / "r.png").string()) + huge);
  const testing::CliResult sweep =
      testing::runCli("sweep " + scene + " -o " + testing::quote((dir / "sweep").string()) + " --spp 1" + huge);
  const testing::CliResult batch = testing::runCli("batch " + testing::quote(jobs) + huge);
  for (const testing::CliResult* r : {&render, &sweep, &batch}) {
    EXPECT_EQ(r->exitCode, 2) << r->err;
    EXPECT_EQ(std::count(r->err.begin(), r->err.end(), '\n'), 1) << r->err;
    EXPECT_NE(r->err.find("needs ~"), std::string::npos) << r->err;
  }
  // The estimate itself, from "needs" on, is the same line in all three.
  auto estimate = [](const std::string& err) { return err.substr(err.find("needs ~")); };
  EXPECT_EQ(estimate(sweep.err), estimate(render.err));
  EXPECT_EQ(estimate(batch.err), estimate(render.err));
  EXPECT_FALSE(std::filesystem::exists(dir / "r.png"));
  EXPECT_FALSE(std::filesystem::exists(dir / "out.png"));
}

TEST(CliHabits, SweepAndBatchTakeThePlanOverrides) {
  testing::ScratchDir dir;
  const std::string scene = testing::quote(std::string(PENUMBRA_SOURCE_DIR) + "/scenes/fig03_shadows.json");
  const std::string small = " -q --set camera.width=24 --set camera.height=16 --disable gate --enable packets";
  const testing::CliResult sweep =
      testing::runCli("sweep " + scene + " -o " + testing::quote((dir / "sweep").string()) + " --spp 1" + small);
  EXPECT_EQ(sweep.exitCode, 0) << sweep.err;
  const testing::CliResult batch = testing::runCli("batch " + scene + " -o " + testing::quote(dir.path().string()) + small);
  EXPECT_EQ(batch.exitCode, 0) << batch.err;
  const testing::CliResult bad = testing::runCli("batch " + scene + " -o " + testing::quote(dir.path().string()) +
                                                 " --disable no-such-pass");
  EXPECT_EQ(bad.exitCode, 2) << bad.err;
}

}  // namespace
// Several scenes: each into OUTPUT/<its name>/ with its own reference, scenes.md over
// them; a bad second scene is refused before the first renders.
TEST(Sweep, SeveralScenesSweepEachIntoItsOwnFolderAndABadOneFailsFirst) {
  testing::ScratchDir dir;
  const std::string scenes = std::string(PENUMBRA_SOURCE_DIR) + "/scenes/";
  const std::string small = " -q --spp 1,2 --set camera.width=24 --set camera.height=16";
  const std::string out = testing::quote((dir / "s").string());
  const testing::CliResult ok = testing::runCli("sweep " + testing::quote(scenes + "fig03_shadows.json") + " " +
                                                testing::quote(scenes + "showcase.json") + " -o " + out + small);
  ASSERT_EQ(ok.exitCode, 0) << ok.err;
  for (const char* name : {"fig03_shadows", "showcase"}) {
    EXPECT_TRUE(std::filesystem::exists(dir / "s" / name / "results.csv")) << name;
    EXPECT_TRUE(std::filesystem::exists(dir / "s" / name / "reference.exr")) << name;
  }
  const std::string md = testing::readFile(dir / "s" / "scenes.md");
  EXPECT_NE(md.find("fig03_shadows/report.md"), std::string::npos) << md;
  EXPECT_NE(md.find("showcase/report.md"), std::string::npos) << md;
  const testing::CliResult bad = testing::runCli("sweep " + testing::quote(scenes + "fig03_shadows.json") + " " +
                                                 testing::quote((dir / "missing.json").string()) + " -o " +
                                                 testing::quote((dir / "t").string()) + small);
  EXPECT_EQ(bad.exitCode, 2) << bad.err;
  EXPECT_NE(bad.err.find("missing.json"), std::string::npos) << bad.err;
  EXPECT_FALSE(std::filesystem::exists(dir / "t" / "fig03_shadows" / "results.csv")) << "nothing rendered";
  const testing::CliResult twice = testing::runCli("sweep " + testing::quote(scenes + "showcase.json") + " " +
                                                   testing::quote(scenes + "showcase.json") + " -o " + out + small);
  EXPECT_EQ(twice.exitCode, 2);
  EXPECT_NE(twice.err.find("would share the folder"), std::string::npos) << twice.err;
}

}  // namespace penumbra
