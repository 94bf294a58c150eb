// Spherical texture mapping through OIIO's TextureSystem on generated textures:
// the checker at known (u, v), the equator, both sides of the seam and the poles,
// colour continuity across the seam, MIP filtering, and a rendered globe.
#include "core/color.h"
#include "io/image_io.h"
#include "io/texture_gen.h"
#include "support/render_fixtures.h"
#include "support/scene_fixtures.h"
#include "support/scratch_dir.h"
#include "geometry/sphere_geometry.h"
#include "trace/texture_lookup.h"
#include <OpenImageIO/imagebuf.h>
#include <gtest/gtest.h>
#include <filesystem>

namespace penumbra {
namespace {

namespace fs = std::filesystem;

Color light() { return Color(kCheckerLight[0], kCheckerLight[1], kCheckerLight[2]); }
Color dark() { return Color(kCheckerDark[0], kCheckerDark[1], kCheckerDark[2]); }

// Writes the generated textures once for the whole suite.
class TextureLookupTest : public ::testing::Test {
 protected:
  static void SetUpTestSuite() {
    dir_ = fs::temp_directory_path() / ("penumbra-texture-test-" + std::to_string(::getpid()));
    fs::create_directories(dir_);
    writeImage((dir_ / "checker.exr").string(), makeTexture("checker", 512, 256));
    writeImage((dir_ / "planet.exr").string(), makeTexture("planet", 512, 256));
    lookup_ = new TextureLookup({(dir_ / "checker.exr").string(), (dir_ / "planet.exr").string()});
  }
  static void TearDownTestSuite() {
    delete lookup_;
    fs::remove_all(dir_);
  }
  // A sharp lookup (a footprint far below one texel) at a sphere direction.
  static Color at(int texture, const Vec3& dir, float footprint = 1e-5f) {
    SurfaceRecord s;
    s.uv = sphericalUv(glm::normalize(dir));
    s.uvPerWorld = sphericalUvPerWorld(1.0f);
    return sample(texture, s.uv, footprint);
  }
  static Color sample(int texture, Vec2 uv, float footprint = 1e-5f) {
    SurfaceRecord s;
    s.uv = uv;
    s.uvPerWorld = sphericalUvPerWorld(1.0f);
    return lookup_->lookup(texture, s, footprint);
  }
  static inline fs::path dir_;
  static inline TextureLookup* lookup_ = nullptr;
};

void expectColor(const Color& got, const Color& want, float tol, const char* what) {
  EXPECT_NEAR(got.r, want.r, tol) << what;
  EXPECT_NEAR(got.g, want.g, tol) << what;
  EXPECT_NEAR(got.b, want.b, tol) << what;
}

}  // namespace

TEST_F(TextureLookupTest, CheckerCellsAtKnownUv) {
  // 8 x 4 cells: cell (i, j) is light when i + j is even.
  expectColor(sample(0, {1.0f / 16, 1.0f / 8}), light(), 1e-3f, "cell (0,0)");
  expectColor(sample(0, {3.0f / 16, 1.0f / 8}), dark(), 1e-3f, "cell (1,0)");
  expectColor(sample(0, {1.0f / 16, 3.0f / 8}), dark(), 1e-3f, "cell (0,1)");
  expectColor(sample(0, {15.0f / 16, 7.0f / 8}), light(), 1e-3f, "cell (7,3)");
}

// The documented mapping inverted: u = 0.5 faces +z and grows eastwards (+x),
// v = 0 is the north pole (+y).
Vec3 directionAt(float u, float v) {
  float theta = kPi * v, phi = 2.0f * kPi * (u - 0.5f);
  return {std::sin(theta) * std::sin(phi), std::cos(theta), std::sin(theta) * std::cos(phi)};
}

TEST_F(TextureLookupTest, EquatorSeamAndPoles) {
  // Just north and south of the equator at +z: cells (4,1) dark and (4,2) light.
  expectColor(at(0, directionAt(0.5f + 1.0f / 16, 0.44f)), dark(), 1e-3f, "north of the equator");
  expectColor(at(0, directionAt(0.5f + 1.0f / 16, 0.56f)), light(), 1e-3f, "south of the equator");
  EXPECT_NEAR(sphericalUv(glm::normalize(Vec3(0.0f, 0.0f, 1.0f))).y, 0.5f, 1e-6f);
  // Either side of the seam at -z the checker flips, exactly as one cell boundary:
  // u just below 1 is cell 7 (dark in row 0), just above 0 is cell 0 (light).
  expectColor(at(0, Vec3(-0.03f, 0.7f, -1.0f)), dark(), 1e-3f, "west of the seam, cell (7,0)");
  expectColor(at(0, Vec3(0.03f, 0.7f, -1.0f)), light(), 1e-3f, "east of the seam, cell (0,0)");
  // Near the poles every longitude still lands in its own cell of the clamped row.
  expectColor(at(0, directionAt(0.3f, 0.01f)), light(), 1e-3f, "near the north pole, cell (2,0)");
  expectColor(at(0, directionAt(0.3f, 0.99f)), dark(), 1e-3f, "near the south pole, cell (2,3)");
  // At the pole itself u is undefined (atan2(0, 0) = 0 -> u = 0.5, a cell
  // boundary): the answer must be finite and lie between the two cells' colours.
  for (const Vec3& pole : {Vec3(0.0f, 1.0f, 0.0f), Vec3(0.0f, -1.0f, 0.0f)}) {
    Color c = at(0, pole);
    ASSERT_TRUE(isFinite(c));
    for (int i = 0; i < 3; ++i) {
      EXPECT_GE(c[i], std::min(light()[i], dark()[i]) - 1e-3f);
      EXPECT_LE(c[i], std::max(light()[i], dark()[i]) + 1e-3f);
    }
  }
}

TEST_F(TextureLookupTest, ColourIsContinuousAcrossTheSeam) {
  // The planet is generated on the sphere, so the two sides of u = 0 match; the
  // lookup must wrap periodically rather than clamp. Compare points 2e-4 rad apart
  // across the seam with the same spacing away from it.
  float worstSeam = 0.0f, worstElsewhere = 0.0f;
  for (float y = -0.9f; y <= 0.9f; y += 0.05f) {
    Color west = at(1, Vec3(-1e-4f, y, -1.0f)), east = at(1, Vec3(1e-4f, y, -1.0f));
    Color a = at(1, Vec3(0.3f - 1e-4f, y, -1.0f)), b = at(1, Vec3(0.3f + 1e-4f, y, -1.0f));
    worstSeam = std::max(worstSeam, maxComponent(glm::abs(west - east)));
    worstElsewhere = std::max(worstElsewhere, maxComponent(glm::abs(a - b)));
  }
  EXPECT_LT(worstSeam, 0.02f);
  EXPECT_LT(worstSeam, worstElsewhere + 0.01f);
  // A wide filter straddling the seam blends both sides instead of clamping.
  Color wide = sample(0, {0.0f, 1.0f / 8}, 0.8f);
  EXPECT_TRUE(isFinite(wide));
}

TEST_F(TextureLookupTest, MipFilteringAveragesTheChecker) {
  // A footprint covering many cells averages them: the mean of light and dark.
  Color mean = 0.5f * (light() + dark());
  Color wide = sample(0, {0.5f, 0.5f}, 8.0f);
  expectColor(wide, mean, 0.08f, "wide footprint ~ checker mean");
  Color sharp = sample(0, {0.5f + 1.0f / 16, 0.5f + 1.0f / 8});
  expectColor(sharp, light(), 1e-3f, "sharp footprint = one cell");
}

TEST_F(TextureLookupTest, RenderedGlobeMultipliesTheLitColour) {
  // An unlit-free setup: ambient only, so each pixel is ambient x texel exactly.
  Scene scene;
  Material m;
  m.name = "globe";
  m.ambient = Color(1.0f);
  m.diffuse = Color(0.0f);
  m.texture = 0;
  scene.materials.push_back(m);
  scene.spheres.push_back(Sphere{Vec3(0.0f), 1.0f, 0});
  scene.camera = axisCamera(Vec3(0, 0, 4), Vec3(0.0f), 30.0f);
  Rig rig(scene);
  rig.ctx.textures = lookup_;
  Image image = rig.render();
  // Pixels whose hit point lies well inside a cell show exactly that cell's
  // colour (ambient 1 x texel): find the hit analytically and predict the cell.
  CameraRays camera(scene.camera);
  int checked = 0;
  for (int y = 4; y < image.height - 4; y += 3) {
    for (int x = 4; x < image.width - 4; x += 3) {
      Ray ray = camera.generate(x + 0.5f, y + 0.5f);
      double t = intersectSphere(scene.spheres[0], ray.origin, ray.dir, 0.0, 1e30);
      if (t < 0.0) continue;
      Vec3 n = glm::normalize(ray.origin + static_cast<float>(t) * ray.dir);
      float u = 0.5f + std::atan2(n.x, n.z) / (2.0f * kPi), v = std::acos(n.y) / kPi;
      float cu = u * 8.0f, cv = v * 4.0f;
      // Skip pixels near a cell edge, where the filter footprint blends cells.
      if (std::abs(cu - std::round(cu)) < 0.15f || std::abs(cv - std::round(cv)) < 0.15f) continue;
      bool isLight = (static_cast<int>(cu) + static_cast<int>(cv)) % 2 == 0;
      expectColor(image.at(x, y), isLight ? light() : dark(), 0.02f, "globe pixel");
      ++checked;
    }
  }
  EXPECT_GT(checked, 20);
}

// 16-bit PNGs are sRGB-encoded like 8-bit ones, and grey + alpha reads as grey.
TEST(TextureFormats, SixteenBitAndGreyAlphaAreLinearisedGrey) {
  const testing::ScratchDir scratch;
  const fs::path& dir = scratch.path();
  auto write = [&](const std::string& name, int channels, OIIO::TypeDesc format) {
    OIIO::ImageBuf buf(OIIO::ImageSpec(8, 4, channels, OIIO::TypeDesc::FLOAT));
    std::vector<float> values(8 * 4 * channels, 0.5f);
    if (channels == 2) for (size_t i = 1; i < values.size(); i += 2) values[i] = 1.0f;  // alpha
    buf.set_pixels(OIIO::ROI::All(), OIIO::TypeDesc::FLOAT, values.data());
    std::string path = (dir / name).string();
    EXPECT_TRUE(buf.write(path, format)) << buf.geterror();
    return path;
  };
  std::vector<std::string> paths = {write("rgb16.png", 3, OIIO::TypeDesc::UINT16),
                                    write("ga8.png", 2, OIIO::TypeDesc::UINT8),
                                    write("rgb8.png", 3, OIIO::TypeDesc::UINT8)};
  TextureLookup lookup(paths);
  SurfaceRecord s;
  s.uv = {0.5f, 0.5f};
  s.uvPerWorld = Vec2(1e-3f);
  const float expected = static_cast<float>(srgbDecode(0.5));  // 0.214
  for (int i = 0; i < 3; ++i) {
    Color c = lookup.lookup(i, s, 1e-3f);
    EXPECT_NEAR(c.r, expected, 3e-3f) << paths[i];
    EXPECT_NEAR(c.g, expected, 3e-3f) << paths[i];
    EXPECT_NEAR(c.b, expected, 3e-3f) << paths[i];
  }
}

// A metallic-roughness map is data: the same 8-bit PNG read as a colour is sRGB-
// decoded (0.5 -> 0.214), read as data it is not (0.5), and metalRoughAt scales the
// material's factors by its B and G. Tolerance 3e-3 (8-bit quantisation).
TEST(TextureFormats, DataTexturesAreNotDecodedAndScaleMetallicAndRoughness) {
  testing::ScratchDir scratch;
  OIIO::ImageBuf buf(OIIO::ImageSpec(8, 4, 3, OIIO::TypeDesc::UINT8));
  std::vector<float> values(8 * 4 * 3, 0.5f);
  for (size_t i = 2; i < values.size(); i += 3) values[i] = 1.0f;  // blue: metallic 1
  buf.set_pixels(OIIO::ROI::All(), OIIO::TypeDesc::FLOAT, values.data());
  const std::string path = (scratch.path() / "mr.png").string();
  ASSERT_TRUE(buf.write(path, OIIO::TypeDesc::UINT8)) << buf.geterror();
  const TextureLookup lookup({path, path}, {false, true});
  SurfaceRecord s;
  s.uv = {0.5f, 0.5f};
  s.uvPerWorld = Vec2(1e-3f);
  EXPECT_NEAR(lookup.lookup(0, s, 1e-3f).g, static_cast<float>(srgbDecode(0.5)), 3e-3f);
  EXPECT_NEAR(lookup.lookup(1, s, 1e-3f).g, 0.5f, 3e-3f);
  Material m;
  m.metalRough = true;
  m.metallic = 0.8f;
  m.roughness = 0.6f;
  m.metalRoughTexture = 1;
  const MetalRough mr = metalRoughAt(m, lookup, s, 1e-3f);
  EXPECT_NEAR(mr.metallic, 0.8f, 3e-3f);
  EXPECT_NEAR(mr.roughness, 0.3f, 3e-3f);
}

// A texture transform (scale, then rotation, then offset) reads the texel an
// untransformed lookup reads at the transformed uv. Tolerance 1e-5.
TEST_F(TextureLookupTest, TransformReadsTheTexelAtTheTransformedUv) {
  const UvTransform t(Vec2(2.0f, 3.0f), Vec2(0.1f, 0.2f), 0.4f);
  for (Vec2 uv : {Vec2(0.13f, 0.27f), Vec2(0.61f, 0.45f), Vec2(0.82f, 0.09f)}) {
    SurfaceRecord s;
    s.uv = uv;
    SurfaceRecord moved;
    Vec2 w = t.apply(uv);
    moved.uv = w - glm::floor(w);
    const Color a = lookup_->lookup(0, s, 0.0f, t);
    const Color b = lookup_->lookup(0, moved, 0.0f, UvTransform(Vec2(1.0f, 1.000001f)));
    expectColorNear(a, b, 1e-5f, "uv " + std::to_string(uv.x) + "," + std::to_string(uv.y));
  }
}

// uv_scale repeats the texture: scaled by (2, 3), the cell at uv is the unscaled
// cell at (2u mod 1, 3v mod 1), and v wraps instead of clamping at the pole.
TEST_F(TextureLookupTest, UvScaleRepeatsTheTexture) {
  SurfaceRecord s;
  s.uvPerWorld = sphericalUvPerWorld(1.0f);
  for (Vec2 uv : {Vec2(1.0f / 32, 1.0f / 24), Vec2(0.3f, 0.45f), Vec2(0.61f, 0.9f), Vec2(0.97f, 0.7f)}) {
    s.uv = uv;
    const Color scaled = lookup_->lookup(0, s, 1e-5f, Vec2(2.0f, 3.0f));
    const Vec2 wrapped(std::fmod(2.0f * uv.x, 1.0f), std::fmod(3.0f * uv.y, 1.0f));
    expectColor(scaled, sample(0, wrapped), 1e-3f, "repeated cell");
  }
}

}  // namespace penumbra
