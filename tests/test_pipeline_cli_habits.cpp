// The command line as pbrt and Mitsuba users type it: -t/--nthreads, -D, --outfile,
// a scene on stdin, `penumbra check`, a close-match suggestion for a mistyped
// option, --trace-pixel refusing an image name, and the exit codes in --help.
#include "io/image_io.h"
#include "support/cli_run.h"
#include <gtest/gtest.h>

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
}

TEST(CliHabits, CheckValidatesWithoutRendering) {
  const auto ok = runCli("check " + quote(kScenes + "showcase.json") + " " + quote(kScenes + "soft_shadows.json"));
  EXPECT_EQ(ok.exitCode, 0) << ok.err;
  EXPECT_NE(ok.out.find("showcase.json: ok (classic, 3 meshes with 16260 triangles"), std::string::npos) << ok.out;
  const auto bad = runCli("check " + quote(kScenes + "showcase.json") + " -D render.max_depth=-1");
  EXPECT_EQ(bad.exitCode, 2);
  EXPECT_NE(bad.err.find("render.max_depth"), std::string::npos) << bad.err;
}

}  // namespace
}  // namespace penumbra
