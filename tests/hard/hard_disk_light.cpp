// Hard cases, class "lights": the disk light through the whole renderer. Both models
// render it without a NaN and within the physically possible radiance; 1 and 2 threads
// give the same pixels; -D reaches its radius; bad keys are one line and exit 2.
#include "hard/hard_cli.h"
#include "hard/hard_support.h"

using namespace penumbra;
using namespace penumbra::hard;

namespace {

// A floor and a back wall (ambient 0) under a disc facing down, tilted towards the wall.
std::string diskJson(const std::string& model, const std::string& light =
    R"({"type": "disk", "center": [0, 1.5, 0], "normal": [0, -1, -0.3], "radius": 0.4, "radiance": 6})") {
  return R"({"camera": {"position": [0, 1.2, 3.5], "look_at": [0, 0.6, 0], "fov": 50, "width": 48, "height": 36, "spp": 2},
  "lights": [)" + light + R"(],
  "materials": {"white": {"ambient": 0, "diffuse": 0.7, "specular": 0}},
  "objects": [
    {"type": "quad", "material": "white", "corner": [-2, 0, 2], "edge1": [4, 0, 0], "edge2": [0, 0, -4]},
    {"type": "quad", "material": "white", "corner": [-2, 0, -2], "edge1": [4, 0, 0], "edge2": [0, 3, 0]},
    {"type": "sphere", "material": "white", "center": [0.5, 0.3, 0.2], "radius": 0.3}],
  "render": {"model": ")" + model + R"(", "light_samples": 4},
  "photons": {"shadow": 20000, "k_shadow": 20, "global": 20000, "caustic": 0, "k_global": 30}})";
}

TEST(HardDiskLight, BothModelsRenderItSanelyAndAlikeOnOneAndTwoThreads) {
  for (const std::string model : {"classic", "physical"}) {
    const std::string json = diskJson(model);
    const RenderResult one = renderJson(json, {}, "disk1", 1), two = renderJson(json, {}, "disk2", 2);
    // Its own pixels show its radiance; nothing lit by it can be brighter.
    expectSane(one, 6.0 * 1.001, model);
    EXPECT_GT(meanPixel(one.image), 1e-3) << model << ": the scene is dark";
    ASSERT_EQ(one.image.pixels.size(), two.image.pixels.size());
    EXPECT_EQ(differingPixels(one.image, two.image, 0.0f), 0) << model << ": 1 and 2 threads differ";
  }
}

// The floor under a facing-down disc lies above its horizon: the render's mean grows
// with the radius given on the command line (radiance fixed, so power grows as R^2).
TEST(HardDiskLight, TheRadiusCanBeSetOnTheCommandLine) {
  const std::string json = diskJson("classic");
  const double small = meanPixel(renderJson(json, {"lights[0].radius=0.2"}, "disk_small").image);
  const double large = meanPixel(renderJson(json, {"lights[0].radius=0.6"}, "disk_large").image);
  EXPECT_GT(large, 2.0 * small);
}

// Bad input: one line naming the JSON path, exit 2.
TEST(HardDiskLight, BadKeysAreOneLineAndExitTwo) {
  const struct {
    const char* light;
    const char* says;
  } cases[] = {
      {R"({"type": "disk", "center": [0, 1, 0], "normal": [0, -1, 0]})", "lights[0]: missing required key \"radius\""},
      {R"({"type": "disk", "center": [0, 1, 0], "normal": [0, 0, 0], "radius": 1})", "lights[0].normal: must be a non-zero vector"},
      {R"({"type": "disk", "center": [0, 1, 0], "normal": [0, -1, 0], "radius": -1})", "lights[0].radius: must be > 0"},
      {R"({"type": "disk", "center": [0, 0, 0], "normal": [0, -1, 0], "radius": 1e-30})", "lights[0].radius: is too small: pi r^2"},
      {R"({"type": "disk", "center": [1e6, 1, 0], "normal": [0, -1, 0], "radius": 1e-3})", "lights[0].radius: must be >= 2^-18"},
      {R"({"type": "disk", "center": [0, 1, 0], "normal": [0, -1, 0], "radius": 1, "edge1": [1, 0, 0]})", "lights[0].edge1"},
      {R"({"type": "disk", "center": [0, 1, 0], "normal": [0, -1, 0], "radius": 1, "radiance": 1, "power": 2})", "lights[0].power: give radiance or power, not both"},
      {R"({"type": "dsk", "center": [0, 1, 0]})", "\"disk\""},
  };
  for (const auto& c : cases) {
    ScratchDir dir;
    const fs::path scene = dir.write("s.json", diskJson("classic", c.light));
    const CliResult r = runCli("render " + quote(scene.string()) + " -o " + quote((dir / "out.png").string()));
    EXPECT_EQ(r.exitCode, 2) << c.light << "\n" << r.err;
    EXPECT_NE(r.err.find(c.says), std::string::npos) << c.light << "\n" << r.err;
    EXPECT_EQ(occurrences(r.err, "\n"), 1u) << c.light << ": one line\n" << r.err;
    EXPECT_FALSE(fs::exists(dir / "out.png")) << c.light;
  }
}

}  // namespace
