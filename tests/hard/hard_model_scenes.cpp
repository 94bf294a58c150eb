// Model files (glTF, OBJ + MTL) given as the scene, through the command line: they
// render in the physical model unless render.model says otherwise (a lit face shows
// rho L, not classic's k_d pi L), an OBJ loads like a glTF file, a model with no
// quality set renders to the model default bound and says which bound stopped it, a
// scene with no light gets one warning, and check counts only the files' materials.
#include "hard/hard_cli.h"
#include "core/scene.h"
#include "io/image_io.h"
#include "plan/render_budget.h"
#include "support/gltf_build.h"

#include <fmt/format.h>
#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

namespace penumbra::hard {
namespace {

using nlohmann::json;

const char* kTiny = " -D camera.width=16 -D camera.height=12 -D photons.global=2000 -D photons.caustic=0";

// A box [0, 2] x [0, 1] x [0, 1] without camera, light or material.
fs::path writeBox(const ScratchDir& dir) {
  const fs::path file = dir.path() / "box.glb";
  EXPECT_TRUE(testing::writeBoxGlb(file.string()));
  return file;
}

// The cube [-1, 1]^3 as an OBJ whose one MTL material has diffuse `kd`: four vertices
// of its own per face (no vertex normals are shared, so shading is flat), wound outwards.
fs::path writeCube(const ScratchDir& dir, const std::string& stem, const std::string& kd) {
  std::string obj = "mtllib " + stem + ".mtl\nusemtl paint\n";
  int first = 1;
  for (int axis = 0; axis < 3; ++axis) {
    for (int side : {-1, 1}) {
      // u, v follow the axis cyclically, so (u, v, axis) is right-handed.
      const int u = (axis + 1) % 3, v = (axis + 2) % 3;
      for (auto [a, b] : {std::pair{-1, -1}, {1, -1}, {1, 1}, {-1, 1}}) {
        int p[3];
        p[axis] = side, p[u] = a, p[v] = b;
        obj += fmt::format("v {} {} {}\n", p[0], p[1], p[2]);
      }
      obj += side > 0 ? fmt::format("f {} {} {}\nf {} {} {}\n", first, first + 1, first + 2, first, first + 2, first + 3)
                      : fmt::format("f {} {} {}\nf {} {} {}\n", first, first + 2, first + 1, first, first + 3, first + 2);
      first += 4;
    }
  }
  dir.write(stem + ".mtl", "newmtl paint\nKd " + kd + "\n");
  return dir.write(stem + ".obj", obj);
}

// A black cube under a point light: every pixel is exactly 0, so the noise is 0 and
// an error bound stops the render after the two passes its estimate needs.
fs::path writeBlackCube(const ScratchDir& dir) {
  dir.write("black.json", R"({"lights": [{"type": "point", "position": [0, 5, 5]}]})");
  return writeCube(dir, "black", "0 0 0");
}

std::string renderCommand(const fs::path& scene, const fs::path& image, const fs::path& stats) {
  return "render " + quote(scene.string()) + " -o " + quote(image.string()) + " --stats " + quote(stats.string()) + kTiny;
}

json statsOf(const fs::path& file) { return json::parse(testing::readFile(file)); }

// The mean of the 4 x 4 pixels around the image's centre.
Color centreMean(const Image& image) {
  Color sum(0.0f);
  for (int y = image.height / 2 - 2; y < image.height / 2 + 2; ++y) {
    for (int x = image.width / 2 - 2; x < image.width / 2 + 2; ++x) sum += image.at(x, y);
  }
  return sum / 16.0f;
}

TEST(HardModelScenes, GltfRendersPhysicalByDefaultAndClassicWhenAsked) {
  const ScratchDir dir;
  const fs::path box = writeBox(dir), stats = dir / "s.json";
  const std::string base = renderCommand(box, dir / "o.png", stats) + " -D camera.spp=1";
  CliResult r = runCli(base);
  ASSERT_EQ(r.exitCode, 0) << r.err;
  EXPECT_EQ(statsOf(stats)["model"], "physical");
  r = runCli(base + " -D render.model=classic");
  ASSERT_EQ(r.exitCode, 0) << r.err;
  EXPECT_EQ(statsOf(stats)["model"], "classic");
  // The settings beside the model choose too.
  dir.write("box.json", R"({"render": {"model": "classic"}})");
  r = runCli(base);
  ASSERT_EQ(r.exitCode, 0) << r.err;
  EXPECT_EQ(statsOf(stats)["model"], "classic");
  // A JSON scene importing the same file keeps the classic default.
  const fs::path scene = dir.write("scene.json", R"({"camera": {"position": [1, 2, 6], "look_at": [1, 0.5, 0.5]},
      "lights": [{"type": "point", "position": [1, 4, 2]}], "objects": [{"type": "mesh", "file": "box.glb"}]})");
  r = runCli(renderCommand(scene, dir / "o.png", stats));
  ASSERT_EQ(r.exitCode, 0) << r.err;
  EXPECT_EQ(statsOf(stats)["model"], "classic");
}

TEST(HardModelScenes, ObjWithMtlIsASceneAndItsLitFaceShowsRhoTimesTheSky) {
  const ScratchDir dir;
  const fs::path cube = writeCube(dir, "cube", "0.8 0.2 0.2"), exr = dir / "o.exr", stats = dir / "s.json";
  CliResult r = runCli("check " + quote(cube.string()));
  ASSERT_EQ(r.exitCode, 0) << r.err;
  EXPECT_EQ(r.out.substr(0, r.out.find('\n')),
            cube.string() + ": ok (physical, 1 meshes with 12 triangles, 0 spheres, 0 lights, 1 materials)");
  EXPECT_NE(r.out.find("adds a camera framing the bounds"), std::string::npos) << r.out;

  // Under a constant sky of radiance 1 a convex Lambert face sees the whole sky: the
  // physical model renders rho L = (0.8, 0.2, 0.2); classic renders k_d pi L (+ ambient).
  dir.write("cube.json", R"({"environment": {"color": 1}, "camera": {"width": 32, "height": 24, "spp": 16}})");
  const std::string base = "render " + quote(cube.string()) + " -o " + quote(exr.string()) + " --stats " +
                           quote(stats.string()) + " -D photons.global=2000 -D photons.caustic=0";
  r = runCli(base);
  ASSERT_EQ(r.exitCode, 0) << r.err;
  EXPECT_EQ(statsOf(stats)["model"], "physical");
  EXPECT_EQ(r.err.find("no quality set"), std::string::npos) << r.err;  // camera.spp is set
  const Color physical = centreMean(readImage(exr.string()));
  EXPECT_NEAR(physical.r, 0.8, 0.04);
  EXPECT_NEAR(physical.g, 0.2, 0.01);
  EXPECT_NEAR(physical.b, 0.2, 0.01);
  r = runCli(base + " -D render.model=classic");
  ASSERT_EQ(r.exitCode, 0) << r.err;
  EXPECT_EQ(statsOf(stats)["model"], "classic");
  EXPECT_GT(centreMean(readImage(exr.string())).r, 0.8f * 3.14f * 0.95f);
}

TEST(HardModelScenes, NoQualitySetRendersToTheModelDefaultAndSaysWhichBoundStopped) {
  const ScratchDir dir;
  const fs::path cube = writeBlackCube(dir), stats = dir / "s.json";
  const std::string base = renderCommand(cube, dir / "o.png", stats);
  CliResult r = runCli(base);
  ASSERT_EQ(r.exitCode, 0) << r.err;
  EXPECT_EQ(occurrences(r.err, "note: " + cube.string() + ": no quality set; passes run until the lighting's noise and "
                                   "bias together are at most 0.005 RMSE or 60 s have passed, whichever comes first"),
            1u)
      << r.err;
  // The bias is checked from 4 passes: a target error waits for it.
  EXPECT_EQ(occurrences(r.err, "budget the model default (--time-limit 60 s, --target-error 0.005 (lighting)): target "
                               "error reached: lighting noise 0 and bias 0, together 0 <= 0.005 after 4 passes"),
            1u)
      << r.err;
  const json budget = statsOf(stats)["budget"];
  EXPECT_EQ(budget["given"], "the model default (--time-limit 60 s, --target-error 0.005 (lighting))");
  EXPECT_EQ(budget["stopped"], "target error reached: lighting noise 0 and bias 0, together 0 <= 0.005");
  EXPECT_EQ(budget["passes"], 4);
}

TEST(HardModelScenes, AnyQualitySettingIsTheUsersAndATileRendersItsOwnPass) {
  const ScratchDir dir;
  const fs::path cube = writeBlackCube(dir), stats = dir / "s.json";
  const std::string base = renderCommand(cube, dir / "o.png", stats);
  CliResult r;
  // Any quality setting is the user's: no default bound.
  for (const char* own : {" -D camera.spp=1", " -D photons.passes=1", " --spp 2"}) {
    r = runCli(base + own);
    ASSERT_EQ(r.exitCode, 0) << r.err;
    EXPECT_EQ(r.err.find("no quality set"), std::string::npos) << own << r.err;
    EXPECT_FALSE(statsOf(stats).contains("budget")) << own;
  }
  r = runCli(base + " --time-limit 30");
  ASSERT_EQ(r.exitCode, 0) << r.err;
  EXPECT_EQ(statsOf(stats)["budget"]["given"], "--time-limit 30 s");
  // A tile renders the scene's own pass: a budget cannot be split.
  r = runCli("render " + quote(cube.string()) + " --tile 1/2 -o " + quote((dir / "t.exr").string()) + kTiny);
  ASSERT_EQ(r.exitCode, 0) << r.err;
  EXPECT_EQ(r.err.find("no quality set"), std::string::npos) << r.err;

  // The rule itself: a model scene without quality takes the default, nothing else does.
  LoadReport model;
  model.modelFile = "cube.gltf";
  EXPECT_TRUE(frameBudget({}, model).modelDefault);
  EXPECT_EQ(frameBudget({}, model).targetError, kModelTargetError);
  EXPECT_EQ(frameBudget({}, model).seconds, kModelTimeLimit);
  EXPECT_EQ(frameBudget({5.0, 0.0}, model).seconds, 5.0);
  EXPECT_FALSE(frameBudget({5.0, 0.0}, model).modelDefault);
  LoadReport sceneFile;
  EXPECT_FALSE(frameBudget({}, sceneFile).any());
  model.qualityGiven = true;
  EXPECT_FALSE(frameBudget({}, model).any());
}

TEST(HardModelScenes, ASceneWithoutLightGetsOneWarning) {
  const ScratchDir dir;
  const fs::path png = dir / "o.png";
  auto warningsOf = [&](const fs::path& scene, const std::string& options) {
    const CliResult r = runCli("render " + quote(scene.string()) + " -o " + quote(png.string()) + options);
    EXPECT_EQ(r.exitCode, 0) << r.err;
    EXPECT_EQ(occurrences(r.err, "note: warning"), 0u) << r.err;
    return r.err;
  };
  const fs::path dark = dir.write("dark.json", R"({"camera": {"width": 16, "height": 12},
      "objects": [{"type": "sphere", "center": [0, 0, -3], "radius": 1}]})");
  const std::string line = "warning: " + dark.string() + ": no light, emissive surface or environment: ";
  std::string err = warningsOf(dark, "");
  EXPECT_EQ(occurrences(err, "warning:"), 1u) << err;
  EXPECT_EQ(occurrences(err, line + "only the classic ambient term shows the surfaces\n"), 1u) << err;
  err = warningsOf(dark, " -D render.ambient=0");
  EXPECT_EQ(occurrences(err, line + "the image is black\n"), 1u) << err;
  err = warningsOf(dark, " -D render.model=physical");
  EXPECT_EQ(occurrences(err, line + "the image is black\n"), 1u) << err;
  const CliResult check = runCli("check " + quote(dark.string()));
  EXPECT_EQ(occurrences(check.err, line), 1u) << check.err;

  // A light, an emitting surface, an environment or a model's default sky: no warning.
  const fs::path lit = dir.write("lit.json", kFloorScene);
  EXPECT_EQ(occurrences(warningsOf(lit, ""), "warning:"), 0u);
  const fs::path glow = dir.write("glow.json", R"({"camera": {"width": 16, "height": 12},
      "materials": {"lamp": {"emission": 2}}, "objects": [{"type": "quad", "corner": [-1, -1, -3],
      "edge1": [2, 0, 0], "edge2": [0, 2, 0], "material": "lamp"}]})");
  EXPECT_EQ(occurrences(warningsOf(glow, ""), "warning:"), 0u);
  EXPECT_EQ(occurrences(warningsOf(dark, " -D environment.color=1"), "warning:"), 0u);
  const fs::path box = writeBox(dir);
  EXPECT_EQ(occurrences(warningsOf(box, std::string(kTiny) + " -D camera.spp=1"), "warning:"), 0u);
  err = warningsOf(box, std::string(kTiny) + " -D camera.spp=1 --no-defaults -D camera.position=[1,2,6] "
                                             "-D camera.look_at=[1,0.5,0.5]");
  EXPECT_EQ(occurrences(err, "warning: " + box.string() + ": no light, emissive surface or environment: the image is "
                                                          "black\n"),
            1u)
      << err;
}

TEST(HardModelScenes, CheckCountsOnlyTheFilesMaterials) {
  const ScratchDir dir;
  auto countLine = [](const fs::path& scene) {
    const CliResult r = runCli("check " + quote(scene.string()));
    EXPECT_EQ(r.exitCode, 0) << r.err;
    const size_t comma = r.out.rfind(", ", r.out.find(" materials)"));
    return r.out.substr(comma + 2, r.out.find(')') - comma - 2);
  };
  EXPECT_EQ(countLine(writeBox(dir)), "0 materials");  // its faces take the implicit default
  EXPECT_EQ(countLine(dir.write("floor.json", kFloorScene)), "0 materials");
  EXPECT_EQ(countLine(dir.write("two.json", R"({"lights": [{"type": "point", "position": [0, 2, 0]}],
      "materials": {"a": {"diffuse": 0.5}, "b": {"diffuse": 0.2}},
      "objects": [{"type": "sphere", "center": [0, 0, -3], "radius": 1, "material": "a"}]})")),
            "2 materials");
  EXPECT_EQ(countLine(writeCube(dir, "cube", "0.5 0.5 0.5")), "1 materials");
}

}  // namespace
}  // namespace penumbra::hard
