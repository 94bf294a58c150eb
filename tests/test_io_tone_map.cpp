// The PNG display transform against its formulas: clamp at exposure 0 is the
// identity (default PNGs keep their bytes), exposure is 2^EV, Reinhard x/(1+x),
// filmic the ACES fit, neutral Khronos PBR Neutral; +Inf is white on every curve; a
// model's scene gets neutral unless a curve is asked; EXR ignores all of it.
#include "core/color.h"
#include "core/error.h"
#include "core/scene.h"
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

TEST(ToneMap, PbrNeutralMatchesKhronosReference) {
  // Below the compression start (0.76 after the offset) a colour only loses its offset:
  // 0.04, or x - 6.25 x^2 under min channel 0.08 (so black stays black).
  DisplayOptions neutral;
  neutral.tone = ToneMap::Neutral;
  EXPECT_EQ(parseToneMap("neutral"), ToneMap::Neutral);
  EXPECT_STREQ(toneMapName(ToneMap::Neutral), "neutral");
  const Color mid = displayColor(Color(0.5f, 0.3f, 0.2f), neutral);
  EXPECT_NEAR(mid.r, 0.46f, 1e-6f);
  EXPECT_NEAR(mid.b, 0.16f, 1e-6f);
  const Color dark = displayColor(Color(0.05f), neutral);  // offset 0.05 - 6.25 x 0.0025
  EXPECT_NEAR(dark.g, 0.05f - 0.034375f, 1e-6f);
  EXPECT_EQ(displayColor(Color(0.0f), neutral), Color(0.0f));
  // Grey 1: peak 0.96, new peak 1 - 0.24^2 / (0.96 - 0.52), and grey stays grey.
  const Color one = displayColor(Color(1.0f), neutral);
  EXPECT_NEAR(one.r, 1.0f - 0.0576f / 0.44f, 1e-6f);
  EXPECT_EQ(one.r, one.b);
  EXPECT_EQ(displayValue(1.0f, neutral), one.g);
  // A bright red: compressed to the new peak, then mixed towards it by
  // 1 - 1 / (0.15 (p - p') + 1): hue kept, desaturated.
  const Color red = displayColor(Color(4.0f, 0.5f, 0.5f), neutral);
  const float p = 4.0f - 0.04f, np = 1.0f - 0.0576f / (p - 0.52f), g = 1.0f - 1.0f / (0.15f * (p - np) + 1.0f);
  EXPECT_NEAR(red.r, np, 1e-5f);
  EXPECT_NEAR(red.g, 0.46f * np / p * (1.0f - g) + np * g, 1e-5f);
  // +Inf is white, negative is black; exposure scales first.
  const float inf = std::numeric_limits<float>::infinity();
  EXPECT_NEAR(displayColor(Color(inf, 0.0f, 0.0f), neutral).g, 1.0f, 1e-6f);
  EXPECT_EQ(displayColor(Color(-1.0f), neutral), Color(0.0f));
  DisplayOptions brighter = neutral;
  brighter.exposure = 1.0f;
  EXPECT_EQ(displayColor(Color(0.25f), brighter), displayColor(Color(0.5f), neutral));
  // The other curves are displayValue per channel.
  const DisplayOptions filmic{0.0f, ToneMap::Filmic};
  EXPECT_EQ(displayColor(Color(0.3f, 2.0f, 0.0f), filmic).g, displayValue(2.0f, filmic));
}

TEST(ToneMap, AModelsSceneGetsNeutralUnlessACurveIsAsked) {
  Scene json, model;
  model.load.modelFile = "model.glb";
  EXPECT_EQ(sceneDisplay({}, json).tone, ToneMap::Clamp);
  EXPECT_EQ(sceneDisplay({}, model).tone, ToneMap::Neutral);
  DisplayOptions asked{0.0f, ToneMap::Clamp, true};
  EXPECT_EQ(sceneDisplay(asked, model).tone, ToneMap::Clamp);
  asked.tone = ToneMap::Reinhard;
  EXPECT_EQ(sceneDisplay(asked, json).tone, ToneMap::Reinhard);
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
