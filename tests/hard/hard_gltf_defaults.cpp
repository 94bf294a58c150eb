// A glTF scene's defaults through the command line: render says once what it added,
// --no-defaults (on render, sweep, batch and check) keeps the file as it is, and
// check prints the file's light count, its bounds and what loading adds. Every check
// is an exact line or count, and the lit image's mean a stated lower bound.
#include "hard/hard_cli.h"
#include "io/image_io.h"
#include "support/gltf_build.h"

#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

namespace penumbra::hard {
namespace {

using nlohmann::json;

// camera.spp sets the quality: no model default bound (hard_model_scenes.cpp tests it).
const char* kSmall =
    " -D camera.width=16 -D camera.height=12 -D camera.spp=1 -D photons.shadow=1000 -D photons.indirect=1000";

// A box [0, 2] x [0, 1] x [0, 1]: no camera, no light.
fs::path writeBox(const ScratchDir& dir) {
  const fs::path file = dir.path() / "box.glb";
  EXPECT_TRUE(testing::writeBoxGlb(file.string()));
  return file;
}

TEST(HardGltfDefaults, RenderFramesAndLightsTheModelAndSaysSoOnce) {
  const ScratchDir dir;
  const fs::path box = writeBox(dir), png = dir / "o.png", stats = dir / "s.json";
  const CliResult r = runCli("render " + quote(box.string()) + " -o " + quote(png.string()) + " --stats " +
                             quote(stats.string()) + kSmall);
  ASSERT_EQ(r.exitCode, 0) << r.err;
  EXPECT_EQ(occurrences(r.err, "note: " + box.string() + ": no camera; one frames the model from ["), 1u) << r.err;
  EXPECT_EQ(occurrences(r.err, "note: " + box.string() + ": no light; the studio environment lights it"), 1u) << r.err;
  EXPECT_EQ(json::parse(testing::readFile(stats))["load"]["defaults_added"], json({"camera", "sky"}));
  // The framed, studio-lit box covers much of the picture: the mean is far from black
  // (a white-ish box, a grey background; 0.1 leaves room for any material's shading).
  const Image image = readImage(png.string());
  double sum = 0.0;
  for (const Color& c : image.pixels) sum += (c.r + c.g + c.b) / 3.0;
  EXPECT_GT(sum / image.pixels.size(), 0.1);

  const CliResult plain = runCli("render " + quote(box.string()) + " -o " + quote(png.string()) + " --stats " +
                                 quote(stats.string()) + " --no-defaults" + kSmall);
  ASSERT_EQ(plain.exitCode, 0) << plain.err;
  EXPECT_EQ(occurrences(plain.err, "no camera"), 0u) << plain.err;
  EXPECT_EQ(occurrences(plain.err, "no light;"), 0u) << plain.err;  // no sky added: one warning instead
  EXPECT_EQ(occurrences(plain.err, "warning: " + box.string() + ": no light"), 1u) << plain.err;
  EXPECT_EQ(json::parse(testing::readFile(stats))["load"]["defaults_added"], json::array());
}

TEST(HardGltfDefaults, CheckPrintsLightsBoundsAndWhatItAdds) {
  const ScratchDir dir;
  const fs::path box = writeBox(dir);
  const std::string head = box.string() + ": ok (physical, 1 meshes with 12 triangles, 0 spheres, 0 lights, 0 materials)\n"
                           "  bounds [0, 0, 0] .. [2, 1, 1] (size 2 x 1 x 1)\n";
  CliResult r = runCli("check " + quote(box.string()));
  ASSERT_EQ(r.exitCode, 0) << r.err;
  EXPECT_EQ(r.out, head + "  adds a camera framing the bounds (the file has none) and the studio environment (the file "
                          "has no light); --no-defaults keeps the file as it is\n");
  r = runCli("check --no-defaults " + quote(box.string()));
  ASSERT_EQ(r.exitCode, 0) << r.err;
  EXPECT_EQ(r.out, head + "  would add a camera framing the bounds (the file has none) and the studio environment (the "
                          "file has no light) without --no-defaults\n");
  // A camera and a light beside the model: nothing to add, no line.
  dir.write("box.json", R"({"camera": {"position": [1, 3, 6], "look_at": [1, 0.5, 0.5]},
                            "lights": [{"type": "point", "position": [1, 4, 2]}]})");
  r = runCli("check " + quote(box.string()));
  ASSERT_EQ(r.exitCode, 0) << r.err;
  EXPECT_EQ(occurrences(r.out, "\n"), 2u) << r.out;
  EXPECT_NE(r.out.find("0 spheres, 1 lights"), std::string::npos) << r.out;
}

TEST(HardGltfDefaults, BatchAndSweepTakeNoDefaultsAndSayANoteOnce) {
  const ScratchDir dir;
  writeBox(dir);
  // Two orbit frames of one model: the orbit places the camera, the sky is added, and
  // its note is said once for the batch.
  const fs::path jobs = dir.write("jobs.json", R"({"set": ["camera.width=16", "camera.height=12", "camera.spp=1",
      "photons.shadow=1000", "photons.indirect=1000"], "jobs": [{"scene": "box.glb", "output": "o_{i}.png",
      "orbit": {"count": 2, "center": [1, 0.5, 0.5], "radius": 5, "height": 1}}]})");
  CliResult r = runCli("batch " + quote(jobs.string()));
  ASSERT_EQ(r.exitCode, 0) << r.err;
  EXPECT_EQ(occurrences(r.err, "no light; the studio environment"), 1u) << r.err;
  EXPECT_EQ(occurrences(r.err, "no camera"), 0u) << r.err;
  // Outputs rendered with the sky are stale without it: no --force needed.
  r = runCli("batch --no-defaults " + quote(jobs.string()));
  ASSERT_EQ(r.exitCode, 0) << r.err;
  EXPECT_EQ(occurrences(r.err, "no light;"), 0u) << r.err;
  EXPECT_EQ(occurrences(r.err, "warning: "), 1u) << r.err;  // said once, not per job
  EXPECT_NE(r.err.find("2 jobs: 2 rendered, 0 up to date"), std::string::npos) << r.err;

  r = runCli("sweep " + quote((dir / "box.glb").string()) + " --spp 1,2 -o " + quote((dir / "sweep").string()) + kSmall);
  ASSERT_EQ(r.exitCode, 0) << r.err;
  EXPECT_EQ(occurrences(r.err, "no light; the studio environment"), 1u) << r.err;
  r = runCli("sweep --no-defaults --force " + quote((dir / "box.glb").string()) + " --spp 1,2 -o " +
             quote((dir / "sweep2").string()) + kSmall);
  ASSERT_EQ(r.exitCode, 0) << r.err;
  EXPECT_EQ(occurrences(r.err, "no light;"), 0u) << r.err;
  EXPECT_EQ(occurrences(r.err, "warning: "), 1u) << r.err;  // said once, not per job
}

}  // namespace
}  // namespace penumbra::hard
