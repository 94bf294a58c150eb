// The geometric views in files: an EXR keeps depth in scene units and normals in
// [-1, 1] (float, A = coverage), a PNG shows the old 0..1 pictures byte for byte,
// a layered EXR keeps the values too, and an EXR header names every setting.
#include "plan/pipeline.h"
#include "core/color.h"
#include "io/aov_display.h"
#include "io/image_io.h"
#include "support/cli_run.h"
#include <OpenImageIO/imageio.h>
#include <gtest/gtest.h>
#include <cmath>
#include <string>
#include <vector>

namespace penumbra {
namespace {

using testing::ScratchDir;

// The camera looks down -z from 5 units; a quad at z = -1 faces it and covers the
// left of the view, the centre pixel's axis ray included (distance 6); a sphere on
// the right shows normals pointing left and down; the far right sees nothing. A
// point light, so the plan keeps the photon maps the header should name.
const char* kScene = R"({
  "name": "aov_rig",
  "camera": {"position": [0, 0, 5], "look_at": [0, 0, 0], "fov": 40, "width": 33, "height": 25},
  "lights": [{"type": "point", "position": [0, 2, 4], "intensity": 10}],
  "materials": {"m": {"diffuse": 0.8}},
  "objects": [{"type": "quad", "corner": [-20, -20, -1], "edge1": [21, 0, 0], "edge2": [0, 40, 0], "material": "m"},
              {"type": "sphere", "center": [1.6, 0, 0], "radius": 0.5, "material": "m"}],
  "render": {"seed": 7, "max_depth": 3}
})";

RenderResult renderTo(const std::string& scene, const std::string& out, const std::string& aov,
                      std::vector<std::string> overrides = {}) {
  RenderRequest req;
  req.scenePath = scene;
  req.outputPath = out;
  req.aov = aov;
  req.session.threads = 2;
  req.overrides = std::move(overrides);
  return runRender(req);
}

// Every channel of an image file as float, with its channel count.
std::vector<float> readChannels(const std::string& path, OIIO::ImageSpec& spec) {
  auto in = OIIO::ImageInput::open(path);
  EXPECT_TRUE(in) << OIIO::geterror();
  if (!in) return {};
  spec = in->spec();
  std::vector<float> v(spec.image_pixels() * spec.nchannels);
  EXPECT_TRUE(in->read_image(0, 0, 0, spec.nchannels, OIIO::TypeDesc::FLOAT, v.data()));
  return v;
}

// The rig's view `aov` rendered to an EXR, read back: RGBA float, as every
// geometric view's file is.
std::vector<float> renderView(const std::string& aov, OIIO::ImageSpec& spec) {
  ScratchDir dir;
  const std::string exr = (dir / (aov + ".exr")).string();
  renderTo(dir.write("rig.json", kScene).string(), exr, aov);
  std::vector<float> v = readChannels(exr, spec);
  EXPECT_EQ(spec.nchannels, 4);
  EXPECT_EQ(spec.channelnames.back(), "A");
  EXPECT_EQ(spec.format, OIIO::TypeDesc::FLOAT);
  return spec.nchannels == 4 ? v : std::vector<float>(spec.image_pixels() * 4, -1.0f);
}

TEST(ExrAov, DepthIsTheDistanceAlongTheRayAndAMissIsZeroWithNoCoverage) {
  OIIO::ImageSpec spec;
  const std::vector<float> v = renderView("depth", spec);
  auto at = [&](int x, int y, int c) { return v[(static_cast<size_t>(y) * spec.width + x) * 4 + c]; };
  EXPECT_NEAR(at(16, 12, 0), 6.0f, 6.0f * 1e-4f);  // centre: the quad, 6 units away
  EXPECT_EQ(at(16, 12, 3), 1.0f);
  // A left pixel off-axis: the plane at z = -1 is 6 / cos(angle to the axis) away.
  const float tanHalf = std::tan(glm::radians(20.0f));
  const float px = (2.5f / 33.0f * 2.0f - 1.0f) * tanHalf * 33.0f / 25.0f;
  const float py = (1.0f - 12.5f / 25.0f * 2.0f) * tanHalf;
  EXPECT_NEAR(at(2, 12, 0), 6.0f * std::sqrt(1.0f + px * px + py * py), 6e-4f);
  EXPECT_EQ(at(32, 0, 0), 0.0f);  // top right: no hit
  EXPECT_EQ(at(32, 0, 3), 0.0f);
}

TEST(ExrAov, NormalsAreWorldSpaceInMinusOneToOne) {
  OIIO::ImageSpec spec;
  const std::vector<float> v = renderView("normal", spec);
  const size_t centre = (12u * spec.width + 16u) * 4;
  EXPECT_NEAR(v[centre + 0], 0.0f, 1e-4f);
  EXPECT_NEAR(v[centre + 1], 0.0f, 1e-4f);
  EXPECT_NEAR(v[centre + 2], 1.0f, 1e-4f);
  float lowestX = 1.0f, lowestY = 1.0f;
  for (size_t i = 0; i < v.size(); i += 4) {
    lowestX = std::min(lowestX, v[i]);
    lowestY = std::min(lowestY, v[i + 1]);
    if (v[i + 3] == 0.0f) EXPECT_EQ(v[i] * v[i] + v[i + 1] * v[i + 1] + v[i + 2] * v[i + 2], 0.0f);
    else EXPECT_NEAR(std::sqrt(v[i] * v[i] + v[i + 1] * v[i + 1] + v[i + 2] * v[i + 2]), 1.0f, 1e-3f) << i;
  }
  EXPECT_LT(lowestX, -0.5f);  // the sphere's left flank
  EXPECT_LT(lowestY, -0.5f);  // and its underside
}

// The PNG holds the depth picture the renderer used to store: (d - nearest) / range,
// misses white, sRGB-encoded; computed here from the EXR's distances.
TEST(ExrAov, DepthPngIsTheOldNormalisedPicture) {
  ScratchDir dir;
  const std::string scene = dir.write("rig.json", kScene).string();
  const std::string exr = (dir / "d.exr").string(), png = (dir / "d.png").string();
  renderTo(scene, exr, "depth");
  renderTo(scene, png, "depth");
  OIIO::ImageSpec es, ps;
  const std::vector<float> d = readChannels(exr, es);
  auto in = OIIO::ImageInput::open(png);
  ASSERT_TRUE(in);
  ps = in->spec();
  std::vector<uint8_t> bytes(ps.image_pixels() * ps.nchannels);
  ASSERT_TRUE(in->read_image(0, 0, 0, ps.nchannels, OIIO::TypeDesc::UINT8, bytes.data()));
  ASSERT_EQ(ps.nchannels, 3);
  float lo = 1e30f, hi = -1e30f;
  for (size_t i = 0; i < d.size(); i += 4)
    if (d[i + 3] > 0.0f) { lo = std::min(lo, d[i]); hi = std::max(hi, d[i]); }
  ASSERT_GT(hi, lo);
  int misses = 0;
  for (size_t p = 0; p < ps.image_pixels(); ++p) {
    const bool hit = d[p * 4 + 3] > 0.0f;
    misses += !hit;
    const float shown = hit ? (d[p * 4] - lo) / (hi - lo) : 1.0f;
    const int expected = shown <= 0.0f ? 0 : shown >= 1.0f ? 255 : static_cast<int>(std::floor(srgbEncode(shown) * 255.0 + 0.5));
    ASSERT_EQ(bytes[p * 3], expected) << p;
  }
  EXPECT_GT(misses, 0);
  // The summary stays; the EXR-only keys do not appear, so the PNG's bytes are as before.
  EXPECT_EQ(readImageAttribute(png, "penumbra:aov"), "depth");
  EXPECT_EQ(readImageAttribute(png, "penumbra:spp"), "");
}

TEST(ExrAov, ExrHeaderNamesTheSettings) {
  ScratchDir dir;
  const std::string exr = (dir / "b.exr").string();
  renderTo(dir.write("rig.json", kScene).string(), exr, "beauty",
           {"camera.spp=2", "photons.shadow=3000", "photons.k_shadow=20", "photons.gate=on"});
  auto attr = [&](const std::string& key) { return readImageAttribute(exr, "penumbra:" + key); };
  const std::vector<std::pair<std::string, std::string>> expected = {
      {"model", "classic"}, {"aov", "beauty"}, {"width", "33"}, {"height", "25"}, {"spp", "2"},
      {"seed", "7"}, {"max_depth", "3"}, {"photons.shadow", "3000"}, {"photons.k_shadow", "20"},
      {"photons.gate", "on"}, {"photons.gate_decision", "on"}, {"photons.lookup", "precomputed"}};
  for (const auto& [key, value] : expected) EXPECT_EQ(attr(key), value) << key;
  EXPECT_FALSE(attr("version").empty());
  EXPECT_NE(attr("version"), "unknown");  // CMake passes the project version
  EXPECT_NE(attr("plan").find("\"gate\""), std::string::npos);
  // A beauty EXR stays RGB half.
  OIIO::ImageSpec spec;
  readChannels(exr, spec);
  EXPECT_EQ(spec.nchannels, 3);
  EXPECT_EQ(spec.format, OIIO::TypeDesc::HALF);
}

// Physical model keys, and the same file for any thread count (bar OIIO's DateTime).
TEST(ExrAov, PhysicalHeaderNamesItsPhotonSettings) {
  ScratchDir dir;
  const std::string exr = (dir / "p.exr").string();
  renderTo(dir.write("rig.json", kScene).string(), exr, "beauty",
           {"render.model=physical", "photons.shadow=3000", "photons.global=5000", "photons.caustic=0", "photons.k_global=30",
            "photons.passes=2"});
  auto attr = [&](const std::string& key) { return readImageAttribute(exr, "penumbra:" + key); };
  EXPECT_EQ(attr("model"), "physical");
  EXPECT_EQ(attr("photons.global"), "5000");
  EXPECT_EQ(attr("photons.k_global"), "30");
  EXPECT_EQ(attr("photons.passes"), "2");
  EXPECT_FALSE(attr("photons.final_global_radius").empty());
  EXPECT_EQ(attr("photons.indirect"), "");  // a classic-only setting is left out
}

// Batch's layered EXR: each geometric layer keeps its values, in float, with NAME.A.
TEST(ExrAov, LayeredExrKeepsPhysicalValues) {
  ScratchDir dir;
  Image beauty(2, 1), depth(2, 1);
  beauty.pixels = {Color(0.25f), Color(2.0f)};
  depth.content = ImageContent::Depth;
  depth.pixels = {Color(12.345678f), Color(0.0f)};
  depth.coverage = {1.0f, 0.0f};
  const std::string exr = (dir / "l.exr").string();
  writeLayeredExr(exr, {{"beauty", beauty}, {"depth", depth}});
  OIIO::ImageSpec spec;
  const std::vector<float> v = readChannels(exr, spec);
  ASSERT_EQ(spec.nchannels, 7);
  EXPECT_EQ(spec.channelnames[6], "depth.A");
  EXPECT_EQ(spec.channelformat(0), OIIO::TypeDesc::HALF);
  EXPECT_EQ(spec.channelformat(3), OIIO::TypeDesc::FLOAT);
  EXPECT_EQ(v[1], 0.25f);
  EXPECT_EQ(v[3], 12.345678f);  // float, not half's 12.34
  EXPECT_EQ(v[6], 1.0f);
  EXPECT_EQ(v[7 + 3], 0.0f);
  EXPECT_EQ(v[7 + 6], 0.0f);
  // The PNG of the depth layer alone is its picture: the hit black, the miss white.
  const std::string png = (dir / "l.png").string();
  writeImage(png, depth);
  const Image shown = readImage(png);
  EXPECT_EQ(shown.pixels[0], Color(0.0f));
  EXPECT_EQ(shown.pixels[1], Color(1.0f));
}

}  // namespace
}  // namespace penumbra
