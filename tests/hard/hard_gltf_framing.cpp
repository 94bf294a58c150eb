// The framing a model gets, measured on rendered images: a glTF sphere with no light
// and no camera, rendered with no options, covers 90% of the image's smaller side
// (its depth view's covered rows or columns), within 5% as promised and within a few
// pixels in fact; --camera picks the file's cameras on every command, and a name or
// index the file lacks is one line and exit 2 before any work.
#include "hard/hard_cli.h"
#include "io/image_io.h"
#include "support/gltf_build.h"

#include <gtest/gtest.h>
#include <cmath>

namespace penumbra::hard {
namespace {

// A UV sphere of radius 1.5 about (1, 2, -3), and cameras 0 "front" at z = 3 and
// 1 "far" at z = 7 looking down -z at it, when `cameras`.
fs::path writeSphere(const ScratchDir& dir, bool cameras) {
  tinygltf::Model m = testing::emptyGltf();
  const float centre[3] = {1, 2, -3};
  testing::addSceneNode(m, testing::addSphereMesh(m, centre, 1.5f));
  if (cameras) {
    testing::addCameraNode(m, 0.7, {1, 2, 3});
    m.cameras.back().name = "front";
    testing::addCameraNode(m, 0.7, {1, 2, 7});
    m.cameras.back().name = "far";
  }
  const fs::path file = dir.path() / (cameras ? "cameras.glb" : "sphere.glb");
  EXPECT_TRUE(testing::writeGltfFile(m, file.string(), true));
  return file;
}

// The rows and columns holding a pixel whose depth view saw the model (a miss has no
// depth: 0).
struct Extent {
  int x0 = 1 << 30, x1 = -1, y0 = 1 << 30, y1 = -1;
};
Extent coverage(const Image& depth) {
  Extent e;
  for (int y = 0; y < depth.height; ++y) {
    for (int x = 0; x < depth.width; ++x) {
      if (!(depth.pixels[size_t(y) * depth.width + x].r > 0.0f)) continue;
      e.x0 = std::min(e.x0, x), e.x1 = std::max(e.x1, x), e.y0 = std::min(e.y0, y), e.y1 = std::max(e.y1, y);
    }
  }
  return e;
}

TEST(HardGltfFraming, AModelWithNoCameraFillsNinetyPercentOfTheSmallerSide) {
  const ScratchDir dir;
  const fs::path sphere = writeSphere(dir, false), exr = dir / "depth.exr";
  // No options but the view: the image is the default 640 x 480, then a portrait one.
  for (const std::string& size : {std::string(), std::string(" -D camera.width=300 -D camera.height=400")}) {
    const CliResult r = runCli("render " + quote(sphere.string()) + " --aov depth -o " + quote(exr.string()) + size);
    ASSERT_EQ(r.exitCode, 0) << r.err;
    const Image depth = readImage(exr.string());
    const Extent e = coverage(depth);
    const int side = std::min(depth.width, depth.height);
    const double across = (depth.width <= depth.height ? e.x1 - e.x0 : e.y1 - e.y0) + 1.0;
    // The sphere's silhouette is the bounding sphere's (vertices on it; the chords of
    // 64 segments lose 0.1%): 90% of the side within a pixel and a half either way.
    EXPECT_NEAR(across / side, 0.9, 0.05 * 0.9) << size;
    EXPECT_NEAR(across, 0.9 * side, 1.5) << size;
    // Centred: the margins either way differ by at most a pixel.
    EXPECT_LE(std::abs(e.x0 - (depth.width - 1 - e.x1)), 1) << size;
    EXPECT_LE(std::abs(e.y0 - (depth.height - 1 - e.y1)), 1) << size;
  }
}

// The depth at the image centre (odd sizes: the pixel on the view axis): the distance
// from the eye to the sphere along the axis.
double centreDepth(const fs::path& exr) {
  const Image depth = readImage(exr.string());
  return depth.pixels[size_t(depth.height / 2) * depth.width + depth.width / 2].r;
}

TEST(HardGltfFraming, CameraPicksTheFilesCamerasOrFramesTheModel) {
  const ScratchDir dir;
  const fs::path model = writeSphere(dir, true), exr = dir / "depth.exr";
  const std::string render = "render " + quote(model.string()) +
                             " --aov depth -D camera.width=33 -D camera.height=25 -o " + quote(exr.string());
  // The sphere's near side is 1.5 before its centre: 4.5 from "front", 8.5 from "far"
  // (a vertex of the tessellation faces each camera).
  for (const auto& [pick, expected] : {std::pair<std::string, double>{"", 4.5},
                                       {" --camera 0", 4.5},
                                       {" --camera front", 4.5},
                                       {" --camera 1", 8.5},
                                       {" --camera far", 8.5}}) {
    const CliResult r = runCli(render + pick);
    ASSERT_EQ(r.exitCode, 0) << pick << r.err;
    EXPECT_NEAR(centreDepth(exr), expected, 0.01) << pick;
  }
  // auto: the eye at r sqrt(1 + 1/t^2) from the centre, t = 0.9 tan(22.5 deg) (the
  // height is the smaller side): 1.5 * 2.86283 - 1.5 = 2.79424 to the near side (a
  // face of the tessellation lies at most r (1 - cos(pi / 32)) = 0.007 inside it).
  const CliResult r = runCli(render + " --camera auto");
  ASSERT_EQ(r.exitCode, 0) << r.err;
  EXPECT_NEAR(centreDepth(exr), 1.5 * std::sqrt(1.0 + 1.0 / std::pow(0.9 * std::tan(M_PI / 8.0), 2)) - 1.5, 0.01);
  EXPECT_EQ(occurrences(r.err, "note: " + model.string() + ": --camera auto; one frames the model from ["), 1u)
      << r.err;
}

// auto on a JSON scene, read from stdin: an exact sphere of radius 2 about (0, 1, 0)
// is framed as the model is, its near side r sqrt(1 + 1/t^2) - r from the eye.
TEST(HardGltfFraming, AutoFramesAJsonSceneFromStdinToo) {
  const ScratchDir dir;
  const fs::path scene = dir.write("ball.json", R"({"camera": {"width": 33, "height": 25},
      "objects": [{"type": "sphere", "center": [0, 1, 0], "radius": 2}]})"),
                 exr = dir / "depth.exr";
  const CliResult r = runShell(quote(PENUMBRA_BINARY) + " render - --camera auto --aov depth -o " + quote(exr.string()) +
                               " < " + quote(scene.string()));
  ASSERT_EQ(r.exitCode, 0) << r.err;
  EXPECT_NEAR(centreDepth(exr), 2.0 * std::sqrt(1.0 + 1.0 / std::pow(0.9 * std::tan(M_PI / 8.0), 2)) - 2.0, 1e-4);
}

TEST(HardGltfFraming, EveryCommandRefusesACameraTheFileLacksInOneLine) {
  const ScratchDir dir;
  const fs::path model = writeSphere(dir, true), out = dir / "o.png";
  const std::string m = quote(model.string());
  dir.write("jobs.json", R"({"jobs": [{"scene": "cameras.glb", "output": "o.png"}]})");
  const std::string line = model.string() + ": --camera 5: no camera 5; the file's cameras: 0 \"front\", 1 \"far\"\n";
  for (const std::string& command :
       {"render " + m + " -o " + quote(out.string()), "sweep " + m + " --spp 1,2 -o " + quote((dir / "sweep").string()),
        "batch " + quote((dir / "jobs.json").string()), "plan " + m, "check " + m}) {
    const CliResult r = runCli(command + " --camera 5");
    EXPECT_EQ(r.exitCode, 2) << command << "\n" << r.err;
    EXPECT_NE(r.err.find(line), std::string::npos) << command << "\n" << r.err;
    EXPECT_EQ(occurrences(r.err, "\n"), 1u) << command << "\n" << r.err;
    EXPECT_FALSE(fs::exists(out)) << command;
  }
  // A camera the file has, or auto, loads (render's were above).
  for (const std::string& command : {"check " + m + " --camera far", "plan " + m + " --camera auto"}) {
    const CliResult r = runCli(command);
    EXPECT_EQ(r.exitCode, 0) << command << "\n" << r.err;
  }
}

// A batch's outputs remember the camera choice: another --camera renders them again.
TEST(HardGltfFraming, BatchOutputsMadeWithAnotherCameraAreStale) {
  const ScratchDir dir;
  writeSphere(dir, true);
  const fs::path jobs = dir.write("jobs.json", R"({"set": ["camera.width=16", "camera.height=12"],
      "jobs": [{"scene": "cameras.glb", "output": "o.png"}]})");
  const std::pair<const char*, const char*> runs[] = {{"", "1 rendered, 0 up to date"},
                                                      {" --camera auto", "1 rendered, 0 up to date"},
                                                      {" --camera auto", "0 rendered, 1 up to date"},
                                                      {" --camera far", "1 rendered, 0 up to date"}};
  for (const auto& [pick, said] : runs) {
    const CliResult r = runCli("batch" + std::string(pick) + " " + quote(jobs.string()));
    ASSERT_EQ(r.exitCode, 0) << r.err;
    EXPECT_EQ(occurrences(r.err, said), 1u) << pick << "\n" << r.err;
  }
}

}  // namespace
}  // namespace penumbra::hard
