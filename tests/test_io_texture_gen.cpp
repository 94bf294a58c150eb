// Procedural textures: the checker layout tests rely on, seamless wrap in u,
// determinism per seed, and the builtin: cache paths.
#include "core/error.h"
#include "io/image_io.h"
#include "io/texture_gen.h"

#include <gtest/gtest.h>

#include <cstdlib>
#include <optional>
#include <filesystem>

namespace fs = std::filesystem;
using namespace penumbra;

namespace {

Color checkerLight() { return Color(kCheckerLight[0], kCheckerLight[1], kCheckerLight[2]); }
Color checkerDark() { return Color(kCheckerDark[0], kCheckerDark[1], kCheckerDark[2]); }

// The pixel whose centre is nearest (u, v).
const Color& at(const Image& image, float u, float v) {
  return image.at(static_cast<int>(u * image.width), static_cast<int>(v * image.height));
}

float difference(const Color& a, const Color& b) { return maxComponent(glm::abs(a - b)); }

// Mean difference between two columns.
float columnDifference(const Image& image, int x0, int x1) {
  float sum = 0.0f;
  for (int y = 0; y < image.height; ++y) sum += difference(image.at(x0, y), image.at(x1, y));
  return sum / image.height;
}

}  // namespace

TEST(TextureGen, CheckerHasEightByFourCells) {
  Image image = makeTexture("checker", 256, 128);
  ASSERT_EQ(image.width, 256);
  ASSERT_EQ(image.height, 128);
  EXPECT_EQ(at(image, 0.01f, 0.01f), checkerLight());    // cell (0, 0)
  EXPECT_EQ(at(image, 0.13f, 0.01f), checkerDark());     // cell (1, 0): u > 1/8
  EXPECT_EQ(at(image, 0.01f, 0.26f), checkerDark());     // cell (0, 1): v > 1/4
  EXPECT_EQ(at(image, 0.13f, 0.26f), checkerLight());    // cell (1, 1)
  EXPECT_EQ(at(image, 0.99f, 0.99f), checkerLight());    // cell (7, 3)
  EXPECT_EQ(at(image, 0.5f + 0.01f, 0.5f + 0.01f), checkerLight());  // cell (4, 2)
  EXPECT_GT(difference(checkerLight(), checkerDark()), 0.5f);
}

TEST(TextureGen, GridHasABrightMeridianAtUZero) {
  Image image = makeTexture("grid", 720, 360);
  const Color& meridian = image.at(0, 100);
  const Color& wrapped = image.at(719, 100);
  const Color& cell = at(image, 7.5f / 360.0f, 97.5f / 180.0f);  // middle of a 15-degree cell
  EXPECT_GT(meridian.r, 0.5f);
  EXPECT_GT(meridian.r, meridian.b);  // yellow, not the blue-grey of other lines
  EXPECT_EQ(meridian, wrapped);       // symmetric about the seam
  EXPECT_LT(maxComponent(cell), 0.05f);
  EXPECT_GT(cell.b, cell.r);          // dark blue
  // A latitude line at 30 degrees north (v = 1/3) is brighter than the cell.
  EXPECT_GT(luminance(at(image, 0.1f, 60.0f / 180.0f)), 5.0f * luminance(cell));
}

TEST(TextureGen, AllTexturesAreFiniteAndInRange) {
  for (const std::string& name : builtinTextureNames()) {
    Image image = makeTexture(name, 128, 64, 3);
    for (const Color& c : image.pixels) {
      ASSERT_TRUE(isFinite(c)) << name;
      EXPECT_GE(std::min(c.r, std::min(c.g, c.b)), 0.0f) << name;
      EXPECT_LE(maxComponent(c), 1.0f) << name;
    }
  }
}

TEST(TextureGen, NoisyTexturesAreSeamlessInU) {
  for (const std::string name : {"planet", "earthlike"}) {
    Image image = makeTexture(name, 512, 256);
    // Column 0 and the last column are neighbours on the sphere: they should
    // differ no more than two neighbouring interior columns do.
    float seam = columnDifference(image, 0, image.width - 1);
    float interior = 0.0f;
    for (int x = 10; x < image.width - 10; x += 50) interior += columnDifference(image, x, x + 1);
    interior /= 10.0f;
    EXPECT_LT(seam, 2.0f * interior + 1e-3f) << name;
    // The top row circles the pole tightly: it is nearly one colour.
    float spread = 0.0f;
    for (int x = 1; x < image.width; ++x)
      spread = std::max(spread, difference(image.at(0, 0), image.at(x, 0)));
    EXPECT_LT(spread, 0.05f) << name;
  }
}

TEST(TextureGen, PlanetHasStructure) {
  Image image = makeTexture("planet", 256, 128);
  // Belts and zones span a clear range of colour, not a flat wash.
  Color lo(kInf), hi(-kInf);
  for (const Color& c : image.pixels) {
    lo = glm::min(lo, c);
    hi = glm::max(hi, c);
  }
  EXPECT_GT(maxComponent(hi - lo), 0.4f);
}

TEST(TextureGen, SameSeedSamePixelsOtherSeedOtherPixels) {
  Image a = makeTexture("planet", 128, 64, 7);
  Image b = makeTexture("planet", 128, 64, 7);
  Image c = makeTexture("planet", 128, 64, 8);
  EXPECT_EQ(a.pixels, b.pixels);
  EXPECT_NE(a.pixels, c.pixels);
  EXPECT_EQ(makeTexture("earthlike", 64, 32, 2).pixels, makeTexture("earthlike", 64, 32, 2).pixels);
}

TEST(TextureGen, UnknownNameListsValidNames) {
  try {
    makeTexture("marble", 64, 32);
    FAIL() << "expected InputError";
  } catch (const InputError& e) {
    std::string message = e.what();
    EXPECT_NE(message.find("'marble'"), std::string::npos) << message;
    for (const std::string& name : builtinTextureNames())
      EXPECT_NE(message.find(name), std::string::npos) << message;
  }
  EXPECT_THROW(makeTexture("checker", 0, 32), InputError);
}

class BuiltinTexturePathTest : public ::testing::Test {
 protected:
  void SetUp() override {
    std::string pattern = (fs::temp_directory_path() / "penumbra-cache-XXXXXX").string();
    ASSERT_NE(mkdtemp(pattern.data()), nullptr);
    dir = pattern;
    const char* old = std::getenv("XDG_CACHE_HOME");
    saved = old ? std::optional<std::string>(old) : std::nullopt;
    setenv("XDG_CACHE_HOME", dir.c_str(), 1);
  }
  void TearDown() override {
    if (saved) setenv("XDG_CACHE_HOME", saved->c_str(), 1);
    else unsetenv("XDG_CACHE_HOME");
    fs::remove_all(dir);
  }
  fs::path dir;
  std::optional<std::string> saved;
};

TEST_F(BuiltinTexturePathTest, GeneratesOnceAndReuses) {
  std::string path = builtinTexturePath("builtin:checker@64");
  EXPECT_TRUE(fs::path(path).is_absolute());
  EXPECT_EQ(fs::path(path).parent_path(), fs::absolute(dir / "penumbra" / "textures"));
  EXPECT_EQ(fs::path(path).extension(), ".exr");
  ASSERT_TRUE(fs::exists(path));

  Image image = readImage(path);
  ASSERT_EQ(image.width, 64);
  ASSERT_EQ(image.height, 32);
  EXPECT_NEAR(image.at(0, 0).r, checkerLight().r, 1e-3f);
  EXPECT_NEAR(image.at(9, 0).r, checkerDark().r, 1e-3f);

  auto written = fs::last_write_time(path);
  EXPECT_EQ(builtinTexturePath("builtin:checker@64"), path);
  EXPECT_EQ(fs::last_write_time(path), written);
  EXPECT_NE(builtinTexturePath("builtin:checker@32"), path);  // width is in the name
  EXPECT_NE(builtinTexturePath("builtin:grid@64"), path);

  size_t files = 0;
  for (const auto& entry : fs::directory_iterator(fs::path(path).parent_path())) {
    EXPECT_EQ(entry.path().filename().string().find(".tmp"), std::string::npos);
    ++files;
  }
  EXPECT_EQ(files, 3u);
}

TEST_F(BuiltinTexturePathTest, RejectsMalformedSpecs) {
  for (const char* spec : {"planet", "builtin:", "builtin:marble", "builtin:planet@",
                           "builtin:planet@abc", "builtin:planet@64x", "builtin:planet@0",
                           "builtin:planet@100000"}) {
    EXPECT_THROW(builtinTexturePath(spec), InputError) << spec;
  }
  EXPECT_TRUE(fs::is_empty(dir) || fs::is_empty(dir / "penumbra" / "textures"));
}
