// The PNG display transform against its formulas: clamp at exposure 0 is the
// identity (default PNGs keep their bytes), exposure is 2^EV, Reinhard x/(1+x),
// filmic the ACES fit; +Inf is white on every curve; EXR ignores all of it.
#include "core/color.h"
#include "core/error.h"
#include "io/image_io.h"
#include "io/tone_map.h"
#include "support/scratch_dir.h"
#include <gtest/gtest.h>
#include <filesystem>
#include <fstream>
#include <limits>
#include <unistd.h>

namespace penumbra {
namespace {

namespace fs = std::filesystem;

TEST(ToneMap, CurvesMatchTheirFormulas) {
  const DisplayOptions clamp{}, reinhard{0.0f, ToneMap::Reinhard}, filmic{0.0f, ToneMap::Filmic};
  for (float x : {0.0f, 0.01f, 0.18f, 0.5f, 0.999f}) EXPECT_EQ(displayValue(x, clamp), x);
  EXPECT_EQ(displayValue(7.0f, clamp), 1.0f);
  EXPECT_FLOAT_EQ(displayValue(1.0f, reinhard), 0.5f);
  EXPECT_FLOAT_EQ(displayValue(3.0f, reinhard), 0.75f);
  EXPECT_NEAR(displayValue(1.0f, filmic), 2.54f / 3.16f, 1e-6f);
  EXPECT_NEAR(displayValue(0.18f, filmic), 0.18f * (2.51f * 0.18f + 0.03f) / (0.18f * (2.43f * 0.18f + 0.59f) + 0.14f), 1e-6f);
  const DisplayOptions plusOne{1.0f, ToneMap::Clamp}, minusTwo{-2.0f, ToneMap::Reinhard};
  EXPECT_FLOAT_EQ(displayValue(0.25f, plusOne), 0.5f);
  EXPECT_FLOAT_EQ(displayValue(4.0f, minusTwo), 0.5f);  // 4 x 2^-2 = 1 -> 1/2
  const float inf = std::numeric_limits<float>::infinity();
  for (const DisplayOptions& o : {clamp, reinhard, filmic}) {
    EXPECT_EQ(displayValue(inf, o), 1.0f);
    EXPECT_EQ(displayValue(-1.0f, o), 0.0f);
  }
  EXPECT_THROW(parseToneMap("aces"), InputError);
}

std::string bytesOf(const fs::path& p) {
  std::ifstream in(p, std::ios::binary);
  return std::string(std::istreambuf_iterator<char>(in), {});
}

TEST(ToneMap, PngGetsTheCurveAndExrStaysLinear) {
  const testing::ScratchDir scratch;
  const fs::path& dir = scratch.path();
  Image image(2, 1);
  image.pixels = {Color(1.0f), Color(3.0f)};
  writeImage((dir / "default.png").string(), image);
  writeImage((dir / "clamp0.png").string(), image, {}, DisplayOptions{});
  EXPECT_EQ(bytesOf(dir / "default.png"), bytesOf(dir / "clamp0.png")) << "the default keeps its bytes";
  writeImage((dir / "reinhard.png").string(), image, {}, DisplayOptions{0.0f, ToneMap::Reinhard});
  const Image png = readImage((dir / "reinhard.png").string());  // linearised back from sRGB
  EXPECT_NEAR(png.pixels[0].r, 0.5f, 0.003f);
  EXPECT_NEAR(png.pixels[1].r, 0.75f, 0.004f);
  writeImage((dir / "reinhard.exr").string(), image, {}, DisplayOptions{3.0f, ToneMap::Reinhard});
  const Image exr = readImage((dir / "reinhard.exr").string());
  EXPECT_EQ(exr.pixels[1].r, 3.0f);
}

}  // namespace
}  // namespace penumbra
