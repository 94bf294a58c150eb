// Output safety, end to end through the binary: an output naming an input is
// refused with the input untouched, bad report paths and bad arguments fail before
// any rendering, and SIGINT during the image write leaves the old output whole.
#include "plan/memory_limit.h"
#include "support/cli_run.h"
#include <gtest/gtest.h>
#include <signal.h>

using namespace penumbra;
using namespace penumbra::testing;

namespace {

const std::string kScenes = std::string(PENUMBRA_SOURCE_DIR) + "/scenes/";

// A tiny scene reading a texture file and an OBJ mesh next to it.
struct InputScene {
  ScratchDir dir;
  fs::path scene, texture, mesh;
  std::string sceneBytes, textureBytes, meshBytes;
  InputScene() {
    texture = dir / "tex.png";
    EXPECT_EQ(runCli("texture checker -o " + quote(texture.string()) + " --width 64").exitCode, 0);
    mesh = dir.write("mesh.obj", readFile(std::string(PENUMBRA_SOURCE_DIR) + "/tests/data/tetra_no_normals.obj"));
    scene = dir.write("scene.json", R"({"name": "inputs",
      "camera": {"position": [0, 0, 4], "look_at": [0, 0, 0], "width": 24, "height": 16},
      "lights": [{"type": "point", "position": [2, 3, 4], "intensity": 20}],
      "materials": {"tex": {"diffuse": 0.7, "texture": {"file": "tex.png"}}, "grey": {"diffuse": 0.5}},
      "objects": [{"type": "sphere", "center": [0, 0, 0], "radius": 1, "material": "tex"},
                  {"type": "mesh", "file": "mesh.obj", "material": "grey"}],
      "photons": {"shadow": 0}})");
    sceneBytes = readFile(scene);
    textureBytes = readFile(texture);
    meshBytes = readFile(mesh);
  }
  std::string render(const std::string& args) const { return "render " + quote(scene.string()) + " " + args; }
  void expectInputsUntouched() const {
    EXPECT_EQ(readFile(scene), sceneBytes);
    EXPECT_EQ(readFile(texture), textureBytes);
    EXPECT_EQ(readFile(mesh), meshBytes);
    EXPECT_EQ(dir.tempFiles(), 0);
  }
};

size_t lines(const std::string& s) { return std::count(s.begin(), s.end(), '\n'); }

}  // namespace

TEST(OutputSafety, TheSceneRendersWhenOutputsAreFine) {
  InputScene s;
  const CliResult r = runCli(s.render("-q -o " + quote((s.dir / "out.png").string())));
  EXPECT_EQ(r.exitCode, 0) << r.err;
  EXPECT_TRUE(fs::exists(s.dir / "out.png"));
  s.expectInputsUntouched();
}

TEST(OutputSafety, OutputNamingAnInputIsRefusedAndTheInputUntouched) {
  InputScene s;
  fs::create_directory(s.dir / "sub");
  fs::create_symlink(s.texture, s.dir / "link.png");
  const std::vector<std::string> refused = {
      "-o " + quote(s.texture.string()),                             // the scene's own texture
      "-o " + quote((s.dir / "sub" / ".." / "tex.png").string()),   // another spelling of it
      "-o " + quote((s.dir / "link.png").string()),                  // a link to it
      "-o " + quote((s.dir / "out.png").string()) + " --stats " + quote(s.scene.string()),
      "-o " + quote((s.dir / "out.png").string()) + " --stats " + quote(s.mesh.string()),
      "-o " + quote(s.scene.string()) + " --trace-pixel 3,4",       // trace JSON over the scene
  };
  for (const std::string& args : refused) {
    const CliResult r = runCli(s.render(args));
    EXPECT_EQ(r.exitCode, 2) << args << ": " << r.err;
    EXPECT_NE(r.err.find("is an input of this render"), std::string::npos) << args << ": " << r.err;
    EXPECT_EQ(lines(r.err), 1u) << r.err;
    s.expectInputsUntouched();
    EXPECT_FALSE(fs::exists(s.dir / "out.png")) << args;
  }
}

TEST(OutputSafety, BadStatsPathFailsBeforeRendering) {
  InputScene s;
  const fs::path out = s.dir / "out.png";
  fs::create_directory(s.dir / "adir");
  for (const fs::path& stats : {s.dir / "missing" / "s.json", s.dir / "adir"}) {
    const CliResult r = runCli(s.render("-o " + quote(out.string()) + " --stats " + quote(stats.string())));
    EXPECT_EQ(r.exitCode, 2) << r.err;
    EXPECT_NE(r.err.find("--stats"), std::string::npos) << r.err;
    EXPECT_EQ(lines(r.err), 1u) << r.err;  // no progress bar, no summary: nothing ran
    EXPECT_FALSE(fs::exists(out));
  }
  // -o and --stats naming one file would have the stats overwrite the image.
  const CliResult same = runCli(s.render("-o " + quote(out.string()) + " --stats " + quote(out.string())));
  EXPECT_EQ(same.exitCode, 2);
  EXPECT_NE(same.err.find("names the same file as -o"), std::string::npos) << same.err;
  s.expectInputsUntouched();
}

TEST(OutputSafety, NegativeSeedAndNonUtf8SetFailBeforeRendering) {
  InputScene s;
  const fs::path out = s.dir / "out.png", stats = s.dir / "s.json";
  const std::string outputs = " -o " + quote(out.string()) + " --stats " + quote(stats.string());
  CliResult r = runCli(s.render("--seed -1" + outputs));
  EXPECT_EQ(r.exitCode, 2) << r.err;
  EXPECT_NE(r.err.find("--seed"), std::string::npos) << r.err;
  r = runCli(s.render("--seed 18446744073709551616" + outputs));  // 2^64
  EXPECT_EQ(r.exitCode, 2) << r.err;
  r = runCli(s.render("--set 'name=\"caf\xe9\"'" + outputs));  // Latin-1, not UTF-8
  EXPECT_EQ(r.exitCode, 2) << r.err;
  EXPECT_NE(r.err.find("not valid UTF-8"), std::string::npos) << r.err;
  EXPECT_EQ(lines(r.err), 1u) << r.err;
  EXPECT_FALSE(fs::exists(out));
  EXPECT_FALSE(fs::exists(stats));
  // The same value in UTF-8 renders, and the largest seed is a seed.
  r = runCli(s.render("-q --seed 18446744073709551615 --set 'name=\"caf\xc3\xa9\"'" + outputs));
  EXPECT_EQ(r.exitCode, 0) << r.err;
  EXPECT_NE(readFile(stats).find("caf\xc3\xa9"), std::string::npos);
}

TEST(OutputSafety, MaxMemoryRefusalSaysTheEstimate) {
  ScratchDir dir;
  const fs::path out = dir / "out.png";
  const CliResult r = runCli("render " + quote(kScenes + "fig14_cornell.json") + " -o " +
                             quote(out.string()) + " --max-memory 64M");
  EXPECT_EQ(r.exitCode, 2) << r.err;
  EXPECT_EQ(lines(r.err), 1u) << r.err;
  for (const char* part : {"fig14_cornell.json: needs ~", "photons ", "image ", "--max-memory is 64.0 MiB"}) {
    EXPECT_NE(r.err.find(part), std::string::npos) << part << " in " << r.err;
  }
  EXPECT_FALSE(fs::exists(out));
  EXPECT_EQ(runCli("render " + quote(kScenes + "fig14_cornell.json") + " -o x.png --max-memory 8Q").exitCode, 2);
}

TEST(OutputSafety, BillionShadowPhotonsAreRefusedOnTheDefaultLimit) {
  // 1e9 photons x ~1 hit per line x 48 B (record, index, transient copy) ~ 45 GiB.
  if (availableMemoryBytes() > 40ull << 30) GTEST_SKIP() << "this machine could hold them";
  ScratchDir dir;
  const fs::path out = dir / "out.png";
  const CliResult r = runCli("render " + quote(kScenes + "fig14_cornell.json") + " -o " +
                             quote(out.string()) + " --gate on --set photons.shadow=1000000000");
  EXPECT_EQ(r.exitCode, 2) << r.err;
  EXPECT_NE(r.err.find("but available memory is"), std::string::npos) << r.err;
  EXPECT_FALSE(fs::exists(out));
}

TEST(OutputSafety, StatsCarryTheEstimate) {
  InputScene s;
  const fs::path stats = s.dir / "s.json";
  const CliResult r = runCli(s.render("-q -o " + quote((s.dir / "o.exr").string()) + " --stats " +
                                      quote(stats.string())));
  ASSERT_EQ(r.exitCode, 0) << r.err;
  const std::string json = readFile(stats);
  for (const char* key : {"\"estimate\"", "\"photon_maps\"", "\"image\"", "\"seconds\"", "\"store_rates\""}) {
    EXPECT_NE(json.find(key), std::string::npos) << key;
  }
}

TEST(OutputSafety, SigintDuringTheImageWriteLeavesNoTempAndTheOldOutput) {
  // The binary's test hook raises SIGINT once the image's temp file exists (between
  // its creation and the rename), so the interrupt lands mid-write every time.
  ScratchDir dir;
  const fs::path out = dir / "out.exr";
  const std::string old = "the previous render, which must survive";
  dir.write("out.exr", old);
  const std::string scene = kScenes + "fig01_depth.json";
  const int status = runCliSignalledAt("temp-file:out.tmp:1",
                                       {"render", scene, "-o", out.string(), "-q", "--aov", "depth", "--set",
                                        "camera.width=64", "--set", "camera.height=64"});
  ASSERT_TRUE(WIFSIGNALED(status) && WTERMSIG(status) == SIGINT)
      << "status " << status << ": the hook did not interrupt the write";
  EXPECT_EQ(dir.tempFiles(), 0);
  EXPECT_EQ(readFile(out), old);
}
