// A glTF model with no light under the studio environment, through the command line:
// a cube shows three face brightnesses in the order of the closed-form irradiance, a
// mirror-metal sphere reflects a bright key over a sky over a darker ground, camera
// rays that miss see the grey, the PNG is the EXR through Khronos PBR Neutral in render
// and batch (a JSON scene's PNG keeps the clamp), and `environment: "studio"` works in
// a JSON scene.
#include "hard/hard_cli.h"
#include "hard/hard_support.h"
#include "core/color.h"
#include "core/lights/studio_environment.h"
#include "io/image_io.h"
#include "io/tone_map.h"
#include "support/gltf_build.h"
#include "support/studio_closed_form.h"

#include <gtest/gtest.h>
#include <cmath>

namespace penumbra::hard {
namespace {

const char* kQuick = " -D photons.shadow=1000 -D photons.indirect=1000 -D photons.global=2000"
                     " -D photons.caustic=2000";
constexpr int kSide = 64;
constexpr double kOrtho = 2.4;

int addMaterial(tinygltf::Model& m, double base, double metallic, double roughness) {
  tinygltf::Material mat;
  mat.pbrMetallicRoughness.baseColorFactor = {base, base, base, 1.0};
  mat.pbrMetallicRoughness.metallicFactor = metallic;
  mat.pbrMetallicRoughness.roughnessFactor = roughness;
  m.materials.push_back(mat);
  return static_cast<int>(m.materials.size()) - 1;
}

// A sidecar JSON placing an orthographic camera (the model keeps no light) at `eye`
// looking at `at`, kOrtho tall, kSide pixels square.
std::string orthoCamera(glm::dvec3 eye, glm::dvec3 at) {
  return "{\"camera\": {\"position\": " + vec(eye.x, eye.y, eye.z) + ", \"look_at\": " + vec(at.x, at.y, at.z) +
         ", \"ortho_height\": " + num(kOrtho) + ", \"width\": " + std::to_string(kSide) +
         ", \"height\": " + std::to_string(kSide) + "}}";
}

// The pixel an orthographic camera at `eye` looking at `at` (up +y) sees `p` in.
std::pair<int, int> pixelOf(glm::dvec3 eye, glm::dvec3 at, glm::dvec3 p) {
  const glm::dvec3 f = glm::normalize(at - eye), r = glm::normalize(glm::cross(f, glm::dvec3(0, 1, 0)));
  const glm::dvec3 u = glm::cross(r, f);
  const double half = 0.5 * kOrtho;
  return {int(std::floor((glm::dot(p - eye, r) / half + 1.0) * 0.5 * kSide)),
          int(std::floor((1.0 - glm::dot(p - eye, u) / half) * 0.5 * kSide))};
}

double patchMean(const Image& im, std::pair<int, int> at, int radius = 2) {
  double sum = 0.0;
  int n = 0;
  for (int y = at.second - radius; y <= at.second + radius; ++y) {
    for (int x = at.first - radius; x <= at.first + radius; ++x) {
      sum += im.pixels[static_cast<size_t>(y) * im.width + x].g;
      ++n;
    }
  }
  return sum / n;
}

const glm::dvec3 kCubeCentre(0.5), kCubeEye = kCubeCentre + 4.0 * glm::normalize(glm::dvec3(1.0));

fs::path writeCube(const ScratchDir& dir) {
  tinygltf::Model m = testing::emptyGltf();
  const float lo[3] = {0, 0, 0}, hi[3] = {1, 1, 1};
  testing::addSceneNode(m, testing::addBoxMesh(m, lo, hi, addMaterial(m, 0.8, 0.0, 1.0)));
  const fs::path file = dir.path() / "cube.glb";
  EXPECT_TRUE(testing::writeGltfFile(m, file.string(), true));
  dir.write("cube.json", orthoCamera(kCubeEye, kCubeCentre));
  return file;
}

TEST(HardStudio, ACubeShowsThreeFaceBrightnessesInTheOrderOfTheirIrradiance) {
  // Seen along (1, 1, 1), the top, front (+z) and right (+x) faces are equally
  // foreshortened: only the light tells them apart. Closed-form E: top 4.67, front 3.13,
  // right 1.99; each face's 5 x 5 patch must keep that order, 10% apart at least.
  const ScratchDir dir;
  const fs::path cube = writeCube(dir), exr = dir / "cube.exr";
  const CliResult r = runCli("render " + quote(cube.string()) + " -o " + quote(exr.string()) +
                             " -D camera.spp=4" + kQuick);
  ASSERT_EQ(r.exitCode, 0) << r.err;
  EXPECT_EQ(occurrences(r.err, ": no light; the studio environment lights it, a grey background behind"), 1u)
      << r.err;
  const Image im = readImage(exr.string());
  const double top = patchMean(im, pixelOf(kCubeEye, kCubeCentre, {0.5, 1.0, 0.5}));
  const double front = patchMean(im, pixelOf(kCubeEye, kCubeCentre, {0.5, 0.5, 1.0}));
  const double right = patchMean(im, pixelOf(kCubeEye, kCubeCentre, {1.0, 0.5, 0.5}));
  std::printf("faces: top %.4f, front %.4f, right %.4f; E %.3f %.3f %.3f\n", top, front, right,
              testing::studioIrradiance({0, 1, 0}), testing::studioIrradiance({0, 0, 1}),
              testing::studioIrradiance({1, 0, 0}));
  EXPECT_GT(top, 1.1 * front);
  EXPECT_GT(front, 1.1 * right);
  EXPECT_GT(right, 0.0);
  // The corners see nothing: the grey, to half-float rounding.
  for (const Color& c : {im.pixels.front(), im.pixels.back()}) EXPECT_NEAR(c.g, studio::kBackground, 1e-3);
}

TEST(HardStudio, AMirrorMetalSphereReflectsKeySkyAndGround) {
  // A smooth metal sphere (base colour 1, roughness 0) seen from +z reflects the key
  // (15 x brighter than the sky at its centre) on its upper left, the sky (0.8 .. 1.2)
  // over its upper half and the ground (0.3) over its lower half: under the old
  // uniform sky every pixel was the same.
  const ScratchDir dir;
  tinygltf::Model m = testing::emptyGltf();
  std::vector<float> p, n;
  std::vector<uint32_t> idx;
  const int rings = 48, segments = 96;
  for (int i = 0; i <= rings; ++i) {
    const double t = testing::kStudioPi * i / rings;
    for (int j = 0; j <= segments; ++j) {
      const double f = 2.0 * testing::kStudioPi * j / segments;
      const float v[3] = {float(std::sin(t) * std::cos(f)), float(std::cos(t)), float(std::sin(t) * std::sin(f))};
      p.insert(p.end(), v, v + 3);
      n.insert(n.end(), v, v + 3);
    }
  }
  for (int i = 0; i < rings; ++i) {
    for (int j = 0; j < segments; ++j) {
      const uint32_t a = i * (segments + 1) + j, b = a + segments + 1;
      idx.insert(idx.end(), {a, a + 1, b, a + 1, b + 1, b});
    }
  }
  testing::addSceneNode(m, testing::addTriangleMesh(m, p, n, {}, idx, addMaterial(m, 1.0, 1.0, 0.0)));
  const fs::path ball = dir.path() / "ball.glb", exr = dir / "ball.exr";
  ASSERT_TRUE(testing::writeGltfFile(m, ball.string(), true));
  dir.write("ball.json", orthoCamera({0, 0, 4}, {0, 0, 0}));
  const CliResult r = runCli("render " + quote(ball.string()) + " -o " + quote(exr.string()) +
                             " -q -D 'render.model=\"physical\"'" + kQuick);
  ASSERT_EQ(r.exitCode, 0) << r.err;
  const Image im = readImage(exr.string());
  double lo = 1e9, hi = 0.0, upper = 0.0, lower = 0.0;
  int nu = 0, nl = 0;
  for (int y = 0; y < kSide; ++y) {
    for (int x = 0; x < kSide; ++x) {
      const double sx = ((x + 0.5) / kSide * 2.0 - 1.0) * 0.5 * kOrtho, sy = (1.0 - (y + 0.5) / kSide * 2.0) * 0.5 * kOrtho;
      if (sx * sx + sy * sy > 0.8) continue;  // well inside the unit disc
      const double v = im.pixels[static_cast<size_t>(y) * kSide + x].g;
      lo = std::min(lo, v);
      hi = std::max(hi, v);
      (sy > 0.1 ? upper : lower) += v;
      (sy > 0.1 ? nu : nl) += 1;
    }
  }
  std::printf("mirror sphere: %.3f .. %.3f, upper mean %.3f, lower mean %.3f\n", lo, hi, upper / nu, lower / nl);
  EXPECT_GT(hi, 5.0 * studio::kHorizon) << "the key's reflection";
  EXPECT_LT(lo, 0.5 * studio::kHorizon) << "the ground's reflection";
  EXPECT_GT(upper / nu, 1.5 * lower / nl) << "sky over ground";
}

// The PNG's bytes against the EXR's values through `tone`, to one code of 255 (the EXR
// holds half floats).
void expectPngIs(const Image& exr, const Image& png, ToneMap tone) {
  ASSERT_EQ(exr.pixels.size(), png.pixels.size());
  DisplayOptions d;
  d.tone = tone;
  double worst = 0.0;
  for (size_t i = 0; i < exr.pixels.size(); ++i) {
    const Color want = displayColor(exr.pixels[i], d);
    for (int c = 0; c < 3; ++c) {
      worst = std::max(worst, std::abs(srgbEncode(want[c]) - srgbEncode(png.pixels[i][c])) * 255.0);
    }
  }
  EXPECT_LE(worst, 1.01) << toneMapName(tone);
}

TEST(HardStudio, AModelsPngIsPbrNeutralAJsonScenesTheClamp) {
  const ScratchDir dir;
  const fs::path cube = writeCube(dir);
  auto render = [&](const std::string& scene, const std::string& out, const std::string& more = "") {
    const CliResult r = runCli("render " + quote(scene) + " -q -o " + quote((dir / out).string()) + kQuick + more);
    EXPECT_EQ(r.exitCode, 0) << r.err;
    return readImage((dir / out).string());
  };
  const Image exr = render(cube.string(), "c.exr");
  expectPngIs(exr, render(cube.string(), "c.png"), ToneMap::Neutral);
  expectPngIs(exr, render(cube.string(), "clamp.png", " --tonemap clamp"), ToneMap::Clamp);
  // batch writes a model's PNG with the same curve: the same pixels as render's.
  const fs::path jobs = dir.write("jobs.json", R"({"set": ["photons.shadow=1000", "photons.indirect=1000",
      "photons.global=2000", "photons.caustic=2000"], "jobs": [{"scene": "cube.glb", "output": "b.png"}]})");
  const CliResult b = runCli("batch -q " + quote(jobs.string()));
  ASSERT_EQ(b.exitCode, 0) << b.err;
  EXPECT_EQ(readImage((dir / "b.png").string()).pixels, readImage((dir / "c.png").string()).pixels);
  // A JSON scene under the studio, named by its key: the clamp, and the grey behind.
  const fs::path json = dir.write("floor.json", std::string(kFloorScene).insert(1, "\"environment\": \"studio\", "));
  const Image floorExr = render(json.string(), "f.exr");
  expectPngIs(floorExr, render(json.string(), "f.png"), ToneMap::Clamp);
  EXPECT_NEAR(floorExr.pixels.front().g, studio::kBackground, 1e-3);
}

}  // namespace
}  // namespace penumbra::hard
