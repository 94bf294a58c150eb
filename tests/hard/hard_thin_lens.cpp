// The thin lens through the command line: a glTF model (no lens of its own) takes it
// from -D, the same pixels for any thread count and other pixels than the pinhole's;
// a bad lens value is one line and exit 2 for every command that loads a scene.
#include "hard/hard_cli.h"
#include "io/image_io.h"
#include "support/gltf_build.h"

#include <gtest/gtest.h>

namespace penumbra::hard {
namespace {

const char* kSmall = " -D camera.width=24 -D camera.height=16 -D camera.spp=4 -D render.aov=depth";

// Two unit cubes, one 3 units behind the other: no camera, no light, no lens.
fs::path writeBoxes(const ScratchDir& dir) {
  tinygltf::Model m = testing::emptyGltf();
  const float lo[3] = {0, 0, 0}, hi[3] = {1, 1, 1};
  const int cube = testing::addBoxMesh(m, lo, hi);
  testing::addSceneNode(m, cube);
  testing::addSceneNode(m, cube, {0.5, 0.0, -3.0});
  const fs::path file = dir.path() / "boxes.glb";
  EXPECT_TRUE(testing::writeGltfFile(m, file.string(), true));
  return file;
}

Image render(const fs::path& model, const fs::path& out, const std::string& extra) {
  const CliResult r = runCli("render " + quote(model.string()) + " -o " + quote(out.string()) + kSmall + extra);
  EXPECT_EQ(r.exitCode, 0) << r.err;
  return readImage(out.string());
}

TEST(HardThinLens, AModelTakesTheLensFromDefinesTheSameForAnyThreadCount) {
  const ScratchDir dir;
  const fs::path box = writeBoxes(dir);
  // The framing camera looks at the pair's centre; focus beyond both instead.
  const std::string lens = " -D camera.f_number=0.05 -D camera.focus_distance=8";
  const Image one = render(box, dir / "a.exr", lens + " --threads 1");
  const Image two = render(box, dir / "b.exr", lens + " --threads 2");
  const Image pinhole = render(box, dir / "c.exr", "");
  ASSERT_EQ(one.pixels.size(), two.pixels.size());
  EXPECT_TRUE(one.pixels == two.pixels) << "a lens render differs between 1 and 2 threads";
  EXPECT_FALSE(one.pixels == pinhole.pixels) << "the lens changed nothing";
}

TEST(HardThinLens, BadLensValuesAreOneLineAndExitTwo) {
  const ScratchDir dir;
  const fs::path box = writeBoxes(dir), scene = dir.write("s.json", kFloorScene);
  const std::pair<const char*, const char*> bad[] = {
      {"camera.aperture_radius=-0.5", "camera.aperture_radius"},
      {"camera.f_number=0", "camera.f_number"},
      {"camera.focus_distance=0", "camera.focus_distance"},
      {"camera.focus_distance=-2", "camera.focus_distance"},
  };
  for (const fs::path& file : {box, scene}) {
    for (const auto& [define, key] : bad) {
      for (const std::string command : {"render", "check"}) {
        const std::string out = command == "render" ? " -o " + quote((dir / "x.png").string()) : "";
        const CliResult r = runCli(command + " " + quote(file.string()) + out + " -D " + define);
        EXPECT_EQ(r.exitCode, 2) << command << " " << define << ": " << r.err;
        EXPECT_EQ(occurrences(r.err, "\n"), 1u) << r.err;
        EXPECT_NE(r.err.find(key), std::string::npos) << r.err;
      }
    }
  }
  EXPECT_FALSE(fs::exists(dir / "x.png"));
}

}  // namespace
}  // namespace penumbra::hard
