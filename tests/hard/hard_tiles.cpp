// Hard cases, class "tiles": a frame rendered as parts (render --tile, --pixel-bounds,
// a jobs file's "tiles") and merged equals the whole render: the same PNG bytes, the
// same EXR pixels and header values (the error figure recomputed by the merge; only
// a one-sample render's probes are pooled, not the whole's number). Parts that do not make one frame, and bad tiles, are refused with one
// line, exit 2, and nothing written.
#include "hard/hard_cli.h"
#include "io/image_io.h"

#include <gtest/gtest.h>

#include <fstream>

namespace penumbra::hard {
namespace {

using testing::readFile;

const std::string kScenes = std::string(PENUMBRA_SOURCE_DIR) + "/scenes/";

// The header keys every render writes, and the EXR's settings (docs/scene-format.md).
const std::vector<std::string> kKeys = {
    "penumbra:scene",    "penumbra:scene_file",    "penumbra:aov",     "penumbra:model",
    "penumbra:settings", "penumbra:error",         "penumbra:error.noise_rmse", "penumbra:error.bias_rmse",
    "penumbra:width",    "penumbra:photons.lookup", "penumbra:plan",   "penumbra:job"};

void writeText(const fs::path& p, const std::string& text) { std::ofstream(p) << text; }

size_t lines(const std::string& text) { return occurrences(text, "\n"); }

// Renders `scene` whole (png and exr) and as `n` tiles, merges them both ways.
void renderAndMerge(const ScratchDir& dir, const std::string& scene, const std::string& options, int n) {
  const std::string base = quote(scene) + " " + options + " -q";
  for (const char* ext : {"png", "exr"}) {
    const CliResult whole = runCli("render " + base + " -o " + quote((dir / "whole.").string() + ext));
    ASSERT_EQ(whole.exitCode, 0) << whole.err;
  }
  std::string parts;
  for (int i = n; i >= 1; --i) {  // any order
    const fs::path part = dir / ("part" + std::to_string(i) + ".exr");
    const CliResult r = runCli("render " + base + " --tile " + std::to_string(i) + "/" + std::to_string(n) + " -o " +
                               quote(part.string()));
    ASSERT_EQ(r.exitCode, 0) << r.err;
    parts += " " + quote(part.string());
  }
  for (const char* ext : {"png", "exr"}) {
    const CliResult m = runCli("merge" + parts + " -q -o " + quote((dir / "merged.").string() + ext));
    ASSERT_EQ(m.exitCode, 0) << m.err;
  }
}

void expectSamePixels(const fs::path& a, const fs::path& b) {
  const Image x = readImage(a.string()), y = readImage(b.string());
  ASSERT_EQ(x.width, y.width);
  ASSERT_EQ(x.height, y.height);
  size_t differ = 0;
  for (size_t i = 0; i < x.pixels.size(); ++i) differ += x.pixels[i] != y.pixels[i];
  EXPECT_EQ(differ, 0u) << a << " and " << b << " differ in " << differ << " pixels";
}

void expectSameKeys(const fs::path& a, const fs::path& b, const std::vector<std::string>& except = {}) {
  for (const std::string& key : kKeys) {
    if (std::find(except.begin(), except.end(), key) != except.end()) continue;
    EXPECT_EQ(readImageAttribute(a.string(), key), readImageAttribute(b.string(), key)) << key;
  }
}

TEST(Tiles, ClassicSamplesMergeToTheSameFiles) {
  const ScratchDir dir;
  renderAndMerge(dir, kScenes + "soft_shadows.json", "-D camera.width=64 -D camera.height=40", 4);
  EXPECT_EQ(readFile(dir / "whole.png"), readFile(dir / "merged.png")) << "the PNG, byte for byte";
  expectSamePixels(dir / "whole.exr", dir / "merged.exr");
  expectSameKeys(dir / "whole.exr", dir / "merged.exr");
  EXPECT_NE(readImageAttribute((dir / "merged.exr").string(), "penumbra:error.noise_rmse"), "");
  // The display transform is the merge's: the parts stay linear.
  const std::string scene = quote(kScenes + "soft_shadows.json") + " -D camera.width=64 -D camera.height=40 -q";
  const std::string tone = " --exposure 1.5 --tonemap filmic -o ";
  ASSERT_EQ(runCli("render " + scene + tone + quote((dir / "filmic.png").string())).exitCode, 0);
  std::string parts;
  for (int i = 1; i <= 4; ++i) parts += " " + quote((dir / ("part" + std::to_string(i) + ".exr")).string());
  ASSERT_EQ(runCli("merge -q" + parts + tone + quote((dir / "merged_filmic.png").string())).exitCode, 0);
  EXPECT_EQ(readFile(dir / "filmic.png"), readFile(dir / "merged_filmic.png"));
}

TEST(Tiles, ClassicOneSampleMergesPixelsAndPoolsItsProbes) {
  const ScratchDir dir;
  writeText(dir / "floor.json", kFloorScene);
  renderAndMerge(dir, (dir / "floor.json").string(), "-D camera.width=40 -D camera.height=30", 4);
  expectSamePixels(dir / "whole.png", dir / "merged.png");
  expectSamePixels(dir / "whole.exr", dir / "merged.exr");
  expectSameKeys(dir / "whole.exr", dir / "merged.exr", {"penumbra:error", "penumbra:error.noise_rmse"});
  const std::string error = readImageAttribute((dir / "merged.exr").string(), "penumbra:error");
  EXPECT_NE(error.find("from probes at"), std::string::npos) << error;
  EXPECT_GT(std::stod(readImageAttribute((dir / "merged.exr").string(), "penumbra:error.noise_rmse")), 0.0);
}

TEST(Tiles, ProgressivePhysicalMergesToTheSameFiles) {
  const ScratchDir dir;
  renderAndMerge(dir, kScenes + "cornell_physical.json",
                 "-D camera.width=48 -D camera.height=30 -D photons.global=20000 -D photons.caustic=20000 "
                 "-D photons.passes=4",
                 4);
  EXPECT_EQ(readFile(dir / "whole.png"), readFile(dir / "merged.png")) << "the PNG, byte for byte";
  expectSamePixels(dir / "whole.exr", dir / "merged.exr");
  expectSameKeys(dir / "whole.exr", dir / "merged.exr");
  EXPECT_NE(readImageAttribute((dir / "merged.exr").string(), "penumbra:error.bias_rmse"), "") << "4 passes: checked";
}

TEST(Tiles, PixelBoundsAnywhereMatchTheWhole) {
  const ScratchDir dir;
  const std::string scene = quote(kScenes + "soft_shadows.json") + " -D camera.width=40 -D camera.height=30 -q";
  ASSERT_EQ(runCli("render " + scene + " -o " + quote((dir / "whole.png").string())).exitCode, 0);
  // Bounds that cut the tracer's 16-pixel tiles and 4x4 packets anywhere.
  const std::vector<std::string> bounds = {"0,13,0,30", "13,40,0,7", "13,27,7,30", "27,40,7,30"};
  std::string parts;
  for (size_t i = 0; i < bounds.size(); ++i) {
    const std::string part = (dir / ("b" + std::to_string(i) + ".exr")).string();
    const CliResult r = runCli("render " + scene + " --pixel-bounds " + bounds[i] + " -o " + quote(part));
    ASSERT_EQ(r.exitCode, 0) << r.err;
    parts += " " + quote(part);
  }
  ASSERT_EQ(runCli("merge" + parts + " -q -o " + quote((dir / "merged.png").string())).exitCode, 0);
  EXPECT_EQ(readFile(dir / "whole.png"), readFile(dir / "merged.png"));
}

// Refused with one line, exit 2, and no output file.
void expectRefused(const CliResult& r, const fs::path& output, const std::string& says) {
  EXPECT_EQ(r.exitCode, 2) << r.err;
  EXPECT_EQ(lines(r.err), 1u) << r.err;
  EXPECT_NE(r.err.find(says), std::string::npos) << r.err;
  EXPECT_FALSE(fs::exists(output)) << output;
}

TEST(Tiles, PartsThatAreNotOneFrameAreRefused) {
  const ScratchDir dir;
  writeText(dir / "s.json", kFloorScene);
  const std::string scene = quote((dir / "s.json").string()) + " -q";
  auto part = [&](const std::string& name, const std::string& how) {
    const std::string path = (dir / name).string();
    const CliResult r = runCli("render " + scene + " " + how + " -o " + quote(path));
    EXPECT_EQ(r.exitCode, 0) << r.err;
    return " " + quote(path);
  };
  const std::string p1 = part("p1.exr", "--tile 1/3"), p2 = part("p2.exr", "--tile 2/3"),
                    p3 = part("p3.exr", "--tile 3/3");
  const fs::path out = dir / "frame.png";
  const std::string to = " -o " + quote(out.string());
  ASSERT_EQ(runCli("merge" + p1 + p2 + p3 + to).exitCode, 0);
  fs::remove(out);
  expectRefused(runCli("merge" + p1 + p3 + to), out, "gap: pixel 0,4 is in no part");
  expectRefused(runCli("merge" + p1 + p2 + p3 + part("over.exr", "--pixel-bounds 3,5,2,6") + to), out, "overlap");
  expectRefused(runCli("merge" + p1 + p2 + part("seed.exr", "--tile 3/3 --seed 9") + to), out, "different jobs");
  // The same job (path, overrides) with the scene file's frame size changed between parts.
  std::string bigger = kFloorScene;
  bigger.replace(bigger.find("\"height\": 12"), 12, "\"height\": 24");
  writeText(dir / "s.json", bigger);
  expectRefused(runCli("merge" + p1 + p2 + part("big.exr", "--tile 3/3") + to), out, "frame");
  expectRefused(runCli("merge " + quote((dir / "none.exr").string()) + to), out, "none.exr");
}

TEST(Tiles, BadTilesAreRefusedBeforeAnyWork) {
  const ScratchDir dir;
  writeText(dir / "s.json", kFloorScene);
  const fs::path out = dir / "part.exr";
  const std::string scene = "render " + quote((dir / "s.json").string()) + " -o " + quote(out.string()) + " ";
  for (const char* bad : {"--tile 0/4", "--tile 5/4", "--tile 1/0", "--tile 2", "--tile 1/13",
                                 "--pixel-bounds 0,16,0,13", "--pixel-bounds 4,4,0,12", "--pixel-bounds -1,3,0,2",
                                 "--pixel-bounds 1,2,3", "--tile 1/2 --time-limit 5", "--tile 1/2 --aov error"}) {
    SCOPED_TRACE(bad);
    expectRefused(runCli(scene + bad), out, std::string(bad).substr(0, 6));
  }
  expectRefused(runCli("render " + quote((dir / "s.json").string()) + " --tile 1/2 -o " +
                       quote((dir / "part.png").string())),
                dir / "part.png", ".exr");
}

TEST(Tiles, JobsFileTilesMergeToTheWholeJobsOutput) {
  const ScratchDir dir;
  const std::string job = R"({"scene": ")" + kScenes + R"(soft_shadows.json", "name": "soft",
      "set": ["camera.width=48", "camera.height=30"], "output": "out/frame.png")";
  writeText(dir / "tiles.json", R"({"jobs": [)" + job + R"(, "tiles": 4}]})");
  writeText(dir / "whole.json", R"({"jobs": [)" + job + "}]}");
  fs::create_directory(dir / "out");
  const CliResult tiles = runCli("batch -q " + quote((dir / "tiles.json").string()));
  ASSERT_EQ(tiles.exitCode, 0) << tiles.err;
  std::string parts;
  for (int i = 1; i <= 4; ++i) {
    const fs::path part = dir / "out" / ("frame.tile" + std::to_string(i) + "of4.exr");
    ASSERT_TRUE(fs::exists(part)) << part;
    parts += " " + quote(part.string());
  }
  const CliResult again = runCli("batch " + quote((dir / "tiles.json").string()));
  EXPECT_EQ(occurrences(again.err, "up to date  "), 4u) << again.err;
  ASSERT_EQ(runCli("merge -q" + parts + " -o " + quote((dir / "merged.png").string())).exitCode, 0);
  ASSERT_EQ(runCli("batch -q " + quote((dir / "whole.json").string())).exitCode, 0);
  EXPECT_EQ(readFile(dir / "out" / "frame.png"), readFile(dir / "merged.png")) << "penumbra:job included";
}

}  // namespace
}  // namespace penumbra::hard
