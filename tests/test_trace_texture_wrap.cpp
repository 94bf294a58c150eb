// Texture lookups through the image module with a texture's own sampler (glTF): the
// texel each wrap mode reads for uvs in [1, 2], above 2 and below 0, bilinear blends
// at the borders, and the scene file's rule (u wraps, v clamps) for a texture without
// a sampler. Expected texels are written out by hand from the glTF spec.
#include "support/scratch_dir.h"
#include "trace/texture_lookup.h"
#include <OpenImageIO/imagebuf.h>
#include <gtest/gtest.h>

namespace penumbra {
namespace {

constexpr int kSide = 4;
// Texel (x, y), row 0 at the top: red (2x + 1) / 16, green (2y + 1) / 16, as data
// (exact in half floats too).
Color texel(int x, int y) { return Color((2.0f * float(x) + 1.0f) / 16.0f, (2.0f * float(y) + 1.0f) / 16.0f, 0.0f); }

class TextureWrapLookup : public ::testing::Test {
 protected:
  static void SetUpTestSuite() {
    scratch_ = new testing::ScratchDir();
    OIIO::ImageBuf buf(OIIO::ImageSpec(kSide, kSide, 3, OIIO::TypeDesc::FLOAT));
    for (int y = 0; y < kSide; ++y) {
      for (int x = 0; x < kSide; ++x) {
        const Color c = texel(x, y);
        const float v[3] = {c.r, c.g, c.b};
        buf.setpixel(x, y, v);
      }
    }
    const std::string path = (scratch_->path() / "grid.exr").string();
    ASSERT_TRUE(buf.write(path)) << buf.geterror();
    auto with = [](TextureWrap w, TexelFilter f) { return TextureSampling{w, w, f, MipFilter::None}; };
    // 0-2: nearest texels, 3-5: bilinear, 6: no sampler (the scene file's rule).
    std::vector<std::optional<TextureSampling>> samplers;
    for (TexelFilter f : {TexelFilter::Nearest, TexelFilter::Linear}) {
      for (TextureWrap w : {TextureWrap::Repeat, TextureWrap::MirroredRepeat, TextureWrap::ClampToEdge}) {
        samplers.push_back(with(w, f));
      }
    }
    samplers.push_back(std::nullopt);
    lookup_ = new TextureLookup(std::vector<std::string>(samplers.size(), path),
                                std::vector<bool>(samplers.size(), true), samplers);
  }
  static void TearDownTestSuite() {
    delete lookup_;
    delete scratch_;
  }
  // A sharp lookup: a footprint far below a texel.
  static Color at(int texture, Vec2 uv) {
    SurfaceRecord s;
    s.uv = uv;
    s.uvPerWorld = Vec2(1.0f);
    return lookup_->lookup(texture, s, 1e-6f);
  }
  static inline testing::ScratchDir* scratch_ = nullptr;
  static inline TextureLookup* lookup_ = nullptr;
};

constexpr int kRepeat = 0, kMirror = 1, kClamp = 2, kLinear = 3, kOwnRule = 6;

Vec2 centre(float tileU, float tileV, int cx, int cy) {
  return Vec2(tileU + (float(cx) + 0.5f) / kSide, tileV + (float(cy) + 0.5f) / kSide);
}

void expectColor(const Color& got, const Color& want, const std::string& what) {
  EXPECT_NEAR(got.r, want.r, 1e-5f) << what;
  EXPECT_NEAR(got.g, want.g, 1e-5f) << what;
}

// v in [1, 2]: repeat reads the rows in order, mirrored repeat upside down, clamp
// the bottom row; u in [-1, 0] likewise for columns (clamp: the left column).
TEST_F(TextureWrapLookup, EachModeReadsTheSpecsTexelForUvOutsideTheUnitSquare) {
  for (int c = 0; c < kSide; ++c) {
    for (int r = 0; r < kSide; ++r) {
      const std::string where = "texel " + std::to_string(c) + "," + std::to_string(r);
      const Vec2 uv = centre(-1.0f, 1.0f, c, r);
      expectColor(at(kRepeat, uv), texel(c, r), "repeat " + where);
      expectColor(at(kMirror, uv), texel(kSide - 1 - c, kSide - 1 - r), "mirror " + where);
      expectColor(at(kClamp, uv), texel(0, kSide - 1), "clamp " + where);
      // u in [2, 3], v in [-2, -1]: repeat and mirror run forwards (even tiles) in u;
      // tile -2 of v is even too; clamp reads the top-right texel.
      const Vec2 far = centre(2.0f, -2.0f, c, r);
      expectColor(at(kRepeat, far), texel(c, r), "repeat far " + where);
      expectColor(at(kMirror, far), texel(c, r), "mirror far " + where);
      expectColor(at(kClamp, far), texel(kSide - 1, 0), "clamp far " + where);
      // v in [-1, 0] and u in [3, 4]: odd tiles, mirrored.
      expectColor(at(kMirror, centre(3.0f, -1.0f, c, r)), texel(kSide - 1 - c, kSide - 1 - r), "mirror odd " + where);
    }
  }
}

// Bilinear at v = 1 (between the bottom row's centre and the next tile's top row):
// repeat blends the bottom and top rows, mirrored repeat and clamp read the bottom
// row alone.
TEST_F(TextureWrapLookup, BilinearAtTheBorderBlendsAsTheModeWraps) {
  const float u = (2.0f + 0.5f) / kSide;
  const Color bottom = texel(2, kSide - 1), top = texel(2, 0);
  expectColor(at(kLinear + kRepeat, Vec2(u, 1.0f)), 0.5f * (bottom + top), "repeat");
  expectColor(at(kLinear + kMirror, Vec2(u, 1.0f)), bottom, "mirror");
  expectColor(at(kLinear + kClamp, Vec2(u, 1.0f)), bottom, "clamp");
  // A quarter texel into the next tile: repeat 3/4 of the top row, mirror the bottom.
  const float v = 1.0f + 0.25f / kSide;
  expectColor(at(kLinear + kRepeat, Vec2(u, v)), 0.25f * bottom + 0.75f * top, "repeat inside");
  expectColor(at(kLinear + kMirror, Vec2(u, v)), bottom, "mirror inside");
}

// Without a sampler, the scene file's rule holds: u wraps, v clamps at 1.
TEST_F(TextureWrapLookup, ATextureWithoutASamplerKeepsTheSceneFilesRule) {
  expectColor(at(kOwnRule, centre(-1.0f, 0.0f, 1, 2)), texel(1, 2), "u wraps");
  expectColor(at(kOwnRule, centre(0.0f, 1.0f, 1, 0)), texel(1, kSide - 1), "v clamps");
}

}  // namespace
}  // namespace penumbra
