// glTF's wrap modes on a texel grid decoded at load (alpha masks, emission maps): the
// texel each mode reads for coordinates inside, above 1, above 2 and below 0, and how
// bilinear filtering blends across each mode's border. Expected texels come from the
// spec's definitions written out by hand, not from the code under test.
#include "core/alpha_mask.h"
#include "core/bilinear.h"
#include <gtest/gtest.h>

namespace penumbra {
namespace {

constexpr int kSide = 4;
// Texel (x, y) holds 10 x + y: every texel is told apart, and a blend of two is too.
float texel(int x, int y) { return float(10 * x + y); }

// uv at the centre of column `cx`, row `cy` of the tile starting at (tileU, tileV).
Vec2 centre(int tileU, int tileV, int cx, int cy) {
  return Vec2(float(tileU) + (float(cx) + 0.5f) / kSide, float(tileV) + (float(cy) + 0.5f) / kSide);
}

float nearestAt(Vec2 uv, TextureWrap wrap) {
  const TextureSampling how{wrap, wrap, TexelFilter::Nearest, MipFilter::None};
  return sampleTexels(kSide, kSide, uv, how, texel);
}

// Tile k of a row of texels: repeat restarts every tile; mirrored repeat runs the
// odd tiles backwards (the tile at -1 is the mirror of tile 0, OpenGL's
// mirror(a) = a >= 0 ? a : -(1 + a)); clamp reads the nearest edge texel outside [0, 1].
int expected(TextureWrap wrap, int tile, int c) {
  switch (wrap) {
    case TextureWrap::Repeat: return c;
    case TextureWrap::MirroredRepeat: return (tile % 2 == 0) ? c : kSide - 1 - c;
    case TextureWrap::ClampToEdge: return tile < 0 ? 0 : tile > 0 ? kSide - 1 : c;
  }
  return -1;
}

TEST(TextureWrap, NearestTexelsForEachModeInsideAboveAndBelowTheUnitSquare) {
  for (TextureWrap wrap : {TextureWrap::Repeat, TextureWrap::MirroredRepeat, TextureWrap::ClampToEdge}) {
    for (int tile : {-3, -2, -1, 0, 1, 2, 3}) {
      for (int c = 0; c < kSide; ++c) {
        for (int r = 0; r < kSide; ++r) {
          const float want = texel(expected(wrap, tile, c), expected(wrap, tile, r));
          EXPECT_EQ(nearestAt(centre(tile, tile, c, r), wrap), want)
              << "wrap " << int(wrap) << " tile " << tile << " texel " << c << "," << r;
        }
      }
    }
  }
}

// v in [1, 2] (the DamagedHelmet's range): repeat reads the texture as in [0, 1],
// mirrored repeat reads it upside down, clamp reads its bottom row.
TEST(TextureWrap, VBetweenOneAndTwo) {
  for (int r = 0; r < kSide; ++r) {
    const Vec2 uv = centre(0, 1, 2, r);
    EXPECT_EQ(nearestAt(uv, TextureWrap::Repeat), texel(2, r));
    EXPECT_EQ(nearestAt(uv, TextureWrap::MirroredRepeat), texel(2, kSide - 1 - r));
    EXPECT_EQ(nearestAt(uv, TextureWrap::ClampToEdge), texel(2, kSide - 1));
  }
}

// Bilinear at a tile border (u = 1, halfway between the last texel's centre and the
// next tile's first): repeat blends the last and first columns, mirrored repeat and
// clamp read the last column twice. Half a texel further in, a texel centre alone.
TEST(TextureWrap, BilinearAtTheBordersBlendsAsEachModeWraps) {
  const float v = (1.0f + 0.5f) / kSide;  // row 1's centre: no blend along v
  auto at = [&](float u, TextureWrap wrap) {
    return sampleTexels(kSide, kSide, Vec2(u, v), TextureSampling{wrap, wrap, TexelFilter::Linear, MipFilter::Auto},
                        texel);
  };
  EXPECT_FLOAT_EQ(at(1.0f, TextureWrap::Repeat), 0.5f * (texel(3, 1) + texel(0, 1)));
  EXPECT_FLOAT_EQ(at(1.0f, TextureWrap::MirroredRepeat), texel(3, 1));
  EXPECT_FLOAT_EQ(at(1.0f, TextureWrap::ClampToEdge), texel(3, 1));
  EXPECT_FLOAT_EQ(at(0.0f, TextureWrap::Repeat), 0.5f * (texel(3, 1) + texel(0, 1)));
  EXPECT_FLOAT_EQ(at(0.0f, TextureWrap::MirroredRepeat), texel(0, 1));
  EXPECT_FLOAT_EQ(at(0.0f, TextureWrap::ClampToEdge), texel(0, 1));
  // A quarter texel past u = 2 under mirrored repeat: tile 2 runs forwards again.
  EXPECT_FLOAT_EQ(at(2.0f + 0.25f / kSide, TextureWrap::MirroredRepeat), texel(0, 1));
  EXPECT_FLOAT_EQ(at(-5.0f + 1.5f / kSide, TextureWrap::ClampToEdge), texel(0, 1));
  EXPECT_FLOAT_EQ(at(7.0f + 1.5f / kSide, TextureWrap::ClampToEdge), texel(3, 1));
}

// A cut-out mask follows its sampler: clamped, v = 1.5 reads the bottom row's alpha;
// repeated (the default), the row at v = 0.5.
TEST(TextureWrap, AlphaMaskReadsWithItsSampler) {
  AlphaMask mask;
  mask.width = 1;
  mask.height = 2;
  mask.alpha = {0, 255};  // top row transparent, bottom opaque
  mask.sampling.texels = TexelFilter::Nearest;
  EXPECT_EQ(mask.at(Vec2(0.5f, 1.25f)), 0.0f);
  mask.sampling.wrapT = TextureWrap::ClampToEdge;
  EXPECT_EQ(mask.at(Vec2(0.5f, 1.25f)), 1.0f);
  mask.sampling.wrapT = TextureWrap::MirroredRepeat;
  EXPECT_EQ(mask.at(Vec2(0.5f, 1.25f)), 1.0f);
  EXPECT_EQ(mask.at(Vec2(0.5f, 1.75f)), 0.0f);
}

}  // namespace
}  // namespace penumbra
