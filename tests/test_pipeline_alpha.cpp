// Coverage in the beauty (render.transparent_background): A is the share of a pixel's
// camera samples that hit, checked against a half-plane's exact half and a disk's
// brute-force area; the colour is premultiplied (EXR) or straight (PNG) by it; the
// default files stay RGB; threads, packets, passes and tiles leave it unchanged.
#include "support/cli_run.h"
#include "support/gltf_build.h"
#include <OpenImageIO/imageio.h>
#include <gtest/gtest.h>
#include <cmath>
#include <string>
#include <vector>

namespace penumbra {
namespace {

using testing::quote;
using testing::readFile;
using testing::runCli;
using testing::ScratchDir;

constexpr int kSide = 16;            // pixels a side
constexpr double kPixel = 2.0 / kSide;  // the orthographic view is 2 x 2 scene units
constexpr double kRadius = 0.6;

// An orthographic camera down -z over [-1, 1]^2; `objects` in front of an empty,
// coloured background, lit by a point light.
std::string scene(const std::string& objects, int spp) {
  return R"({"camera": {"position": [0, 0, 5], "look_at": [0, 0, 0], "ortho_height": 2, "width": 16,
             "height": 16, "spp": )" + std::to_string(spp) + R"(},
  "lights": [{"type": "point", "position": [0, 1, 4], "intensity": 20}],
  "materials": {"m": {"diffuse": [0.8, 0.5, 0.3]}},
  "objects": [)" + objects + R"(],
  "render": {"seed": 3, "background": [0.2, 0.4, 0.6]}})";
}
const std::string kDisk = R"({"type": "sphere", "center": [0, 0, 0], "radius": 0.6, "material": "m"})";
// A quad whose right edge runs down the middle of pixel column 8 (x = 0.0625).
const std::string kHalf =
    R"({"type": "quad", "corner": [-5, -5, 0], "edge1": [5.0625, 0, 0], "edge2": [0, 10, 0], "material": "m"})";

struct File {
  int width = 0, height = 0, channels = 0;
  std::vector<std::string> names;
  std::vector<float> values;  // as stored, as float; 8-bit files in [0, 1]
  float at(int x, int y, int c) const { return values[(static_cast<size_t>(y) * width + x) * channels + c]; }
};

File readBack(const std::string& path) {
  File f;
  OIIO::ImageSpec config;
  config.attribute("oiio:UnassociatedAlpha", 1);  // a PNG's colour as stored, not premultiplied on reading
  auto in = OIIO::ImageInput::open(path, &config);
  EXPECT_TRUE(in) << OIIO::geterror();
  if (!in) return f;
  const OIIO::ImageSpec& spec = in->spec();
  f.width = spec.width;
  f.height = spec.height;
  f.channels = spec.nchannels;
  f.names = spec.channelnames;
  f.values.resize(spec.image_pixels() * spec.nchannels);
  EXPECT_TRUE(in->read_image(0, 0, 0, spec.nchannels, OIIO::TypeDesc::FLOAT, f.values.data()));
  return f;
}

// Renders `json` to `out` with the extra command-line `options`; the file read back.
File render(const ScratchDir& dir, const std::string& json, const std::string& out, const std::string& options = "") {
  const std::string path = (dir / out).string();
  const testing::CliResult r =
      runCli("render " + quote(dir.write("scene.json", json).string()) + " -q " + options + " -o " + quote(path));
  EXPECT_EQ(r.exitCode, 0) << r.err;
  return readBack(path);
}

const std::string kOn = "-D render.transparent_background=true";

// The share of pixel (x, y) inside the disk of radius kRadius at the origin, by a
// 400 x 400 grid of point tests (an error below 1e-3).
double diskShare(int x, int y) {
  constexpr int n = 400;
  int inside = 0;
  for (int j = 0; j < n; ++j) {
    for (int i = 0; i < n; ++i) {
      const double px = -1.0 + (x + (i + 0.5) / n) * kPixel, py = 1.0 - (y + (j + 0.5) / n) * kPixel;
      inside += px * px + py * py < kRadius * kRadius;
    }
  }
  return double(inside) / (double(n) * n);
}

TEST(Alpha, DefaultFilesStayRgb) {
  const ScratchDir dir;
  EXPECT_EQ(render(dir, scene(kDisk, 4), "a.png").channels, 3);
  EXPECT_EQ(render(dir, scene(kDisk, 4), "a.exr").channels, 3);
}

TEST(Alpha, HalfPlaneCoversExactlyHalfOfItsEdgePixels) {
  const ScratchDir dir;
  const File f = render(dir, scene(kHalf, 64), "half.exr", kOn);
  ASSERT_EQ(f.channels, 4);
  EXPECT_EQ(f.names, (std::vector<std::string>{"R", "G", "B", "A"}));
  for (int y = 0; y < kSide; ++y) {
    EXPECT_EQ(f.at(7, y, 3), 1.0f) << y;
    // Each of the pixel's two (0,2)-sequences puts 16 of its 32 points left of the middle.
    EXPECT_EQ(f.at(8, y, 3), 0.5f) << y;
    EXPECT_EQ(f.at(9, y, 3), 0.0f) << y;
    for (int c = 0; c < 3; ++c) EXPECT_EQ(f.at(9, y, c), 0.0f) << "the background adds nothing";
  }
}

TEST(Alpha, DiskCoverageIsTheAreaFractionOfEachPixel) {
  const ScratchDir dir;
  const File f = render(dir, scene(kDisk, 256), "disk.exr", kOn);
  ASSERT_EQ(f.channels, 4);
  double area = 0.0, worst = 0.0;
  for (int y = 0; y < kSide; ++y) {
    for (int x = 0; x < kSide; ++x) {
      const double share = diskShare(x, y), a = f.at(x, y, 3);
      if (share == 0.0 || share == 1.0) {
        EXPECT_EQ(a, share) << x << "," << y;
      }
      worst = std::max(worst, std::abs(a - share));
      area += a * kPixel * kPixel;
    }
  }
  // 256 stratified samples: an edge pixel's share within a few hundredths.
  EXPECT_LT(worst, 0.03);
  EXPECT_NEAR(area, M_PI * kRadius * kRadius, 0.003 * M_PI * kRadius * kRadius);
}

TEST(Alpha, ColourIsPremultipliedInExrAndStraightInPng) {
  const ScratchDir dir;
  const std::string json = scene(kDisk, 64);
  const File opaque = render(dir, json, "opaque.exr"), clear = render(dir, json, "clear.exr", kOn);
  const File opaquePng = render(dir, json, "opaque.png"), clearPng = render(dir, json, "clear.png", kOn);
  ASSERT_EQ(clear.channels, 4);
  ASSERT_EQ(clearPng.channels, 4);
  const float background[3] = {0.2f, 0.4f, 0.6f};
  int edges = 0;
  for (int y = 0; y < kSide; ++y) {
    for (int x = 0; x < kSide; ++x) {
      const float a = clear.at(x, y, 3);
      // The opaque pixel is the clear one plus the background over the samples that missed.
      for (int c = 0; c < 3; ++c)
        EXPECT_NEAR(opaque.at(x, y, c), clear.at(x, y, c) + (1.0f - a) * background[c], 2e-3f) << x << "," << y;
      // PNG alpha is linear, 8-bit; its colour is the surface's, not darkened at the edge.
      EXPECT_EQ(std::lround(clearPng.at(x, y, 3) * 255.0f), std::lround(std::floor(a * 255.0f + 0.5f)))
          << x << "," << y;
      if (a == 1.0f) {
        for (int c = 0; c < 3; ++c) EXPECT_EQ(clearPng.at(x, y, c), opaquePng.at(x, y, c));
      } else if (a == 0.0f) {
        for (int c = 0; c < 4; ++c) EXPECT_EQ(clearPng.at(x, y, c), 0.0f) << "background: RGBA 0";
      } else if (a > 0.25f) {
        ++edges;
        for (int c = 0; c < 3; ++c) {
          const double straight = clear.at(x, y, c) / a;
          const double srgb = straight <= 0.0031308 ? 12.92 * straight : 1.055 * std::pow(straight, 1 / 2.4) - 0.055;
          EXPECT_NEAR(clearPng.at(x, y, c), std::min(srgb, 1.0), 1.5 / 255) << x << "," << y;
        }
      }
    }
  }
  EXPECT_GT(edges, 8);
}

TEST(Alpha, SameForAnyThreadCountAndWithoutPackets) {
  const ScratchDir dir;
  const std::string json = scene(kDisk, 16);
  const File two = render(dir, json, "two.exr", kOn + " --threads 2");
  const File one = render(dir, json, "one.exr", kOn + " --threads 1");
  const File single = render(dir, json, "single.exr", kOn + " -D render.packets=false");
  EXPECT_EQ(two.values, one.values);
  EXPECT_EQ(two.values, single.values);
}

TEST(Alpha, ProgressivePassesAverageTheirCoverage) {
  const ScratchDir dir;
  const File f = render(dir, scene(kHalf, 16), "passes.exr",
                        kOn + " -D render.model=physical -D photons.passes=3 -D photons.global=2000 "
                              "-D photons.caustic=0");
  ASSERT_EQ(f.channels, 4);
  for (int y = 0; y < kSide; ++y) {
    EXPECT_EQ(f.at(7, y, 3), 1.0f);
    EXPECT_EQ(f.at(8, y, 3), 0.5f) << "each pass's points are whole strata";
    EXPECT_EQ(f.at(9, y, 3), 0.0f);
  }
}

TEST(Alpha, TilesMergeToTheWholeRgba) {
  const ScratchDir dir;
  const std::string json = dir.write("disk.json", scene(kDisk, 16)).string();
  const std::string base = "render " + quote(json) + " -q " + kOn;
  std::string parts;
  for (int i = 1; i <= 3; ++i) {
    const std::string part = (dir / ("part" + std::to_string(i) + ".exr")).string();
    ASSERT_EQ(runCli(base + " --tile " + std::to_string(i) + "/3 -o " + quote(part)).exitCode, 0);
    parts += " " + quote(part);
  }
  for (const char* ext : {"png", "exr"}) {
    const std::string whole = (dir / "whole.").string() + ext, merged = (dir / "merged.").string() + ext;
    ASSERT_EQ(runCli(base + " -o " + quote(whole)).exitCode, 0);
    const testing::CliResult m = runCli("merge" + parts + " -q -o " + quote(merged));
    ASSERT_EQ(m.exitCode, 0) << m.err;
    const File a = readBack(whole), b = readBack(merged);
    EXPECT_EQ(a.channels, 4);
    EXPECT_EQ(a.values, b.values) << ext;
    if (std::string(ext) == "png") {
      EXPECT_EQ(readFile(whole), readFile(merged));
    }
  }
}

// A model file takes the key as a JSON scene does (-D on its settings): the framed box
// is opaque, the margins around it (0, 0, 0, 0).
TEST(Alpha, AModelFileTakesTheKey) {
  const ScratchDir dir;
  tinygltf::Model m = testing::emptyGltf();
  const float lo[3] = {0, 0, 0}, hi[3] = {2, 1, 1};
  testing::addSceneNode(m, testing::addBoxMesh(m, lo, hi));
  const std::string box = (dir / "box.glb").string(), png = (dir / "box.png").string();
  ASSERT_TRUE(testing::writeGltfFile(m, box, true));
  const testing::CliResult r = runCli("render " + quote(box) + " -q -D camera.width=24 -D camera.height=16 " + kOn +
                                      " -o " + quote(png));
  ASSERT_EQ(r.exitCode, 0) << r.err;
  const File f = readBack(png);
  ASSERT_EQ(f.channels, 4);
  int clear = 0, solid = 0;
  for (int y = 0; y < f.height; ++y) {
    for (int x = 0; x < f.width; ++x) {
      if (f.at(x, y, 3) == 1.0f) ++solid;
      if (f.at(x, y, 3) > 0.0f) continue;
      ++clear;
      for (int c = 0; c < 3; ++c) EXPECT_EQ(f.at(x, y, c), 0.0f) << x << "," << y;
    }
  }
  EXPECT_EQ(f.at(0, 0, 3), 0.0f) << "a corner of the frame is margin";
  EXPECT_GT(clear, 0);
  EXPECT_GT(solid, f.width * f.height / 8) << "the framed box (its bounding sphere 90% of the height) shows";
}

TEST(Alpha, NotABoolIsOneLineAndExitTwo) {
  const ScratchDir dir;
  const testing::CliResult r = runCli("render " + quote(dir.write("s.json", scene(kDisk, 1)).string()) +
                                      " -q -D render.transparent_background=3 -o " + quote((dir / "x.png").string()));
  EXPECT_EQ(r.exitCode, 2);
  EXPECT_NE(r.err.find("transparent_background"), std::string::npos) << r.err;
  EXPECT_FALSE(std::filesystem::exists(dir / "x.png"));
}

}  // namespace
}  // namespace penumbra
