// Adaptive pixel sampling through the pipeline: the same pixels for one and two
// threads in both models, the spp view counting every camera sample (and holding the
// per-pixel cap), the pixels of uniform sampling when it is off, and the error
// estimate against the noise measured between two seeds.
#include "plan/pipeline.h"
#include "support/render_file.h"
#include <gtest/gtest.h>
#include <algorithm>
#include <cmath>
#include <cstring>
#include <string>
#include <vector>

namespace penumbra {
namespace {

const std::string kScenes = std::string(PENUMBRA_SOURCE_DIR) + "/scenes/";
constexpr int kPasses = 6, kMaxSpp = 4;

// cornell_physical small: 48 x 48, 6 passes of 20k + 20k photons; a low threshold so
// many pixels take extra samples, at most kMaxSpp a pass.
std::vector<std::string> physical(const std::string& adaptive) {
  return {"camera.width=48", "camera.height=48", "photons.global=20000", "photons.caustic=20000",
          "photons.passes=" + std::to_string(kPasses), "render.adaptive=" + adaptive, "render.adaptive_threshold=1",
          "render.adaptive_max_spp=" + std::to_string(kMaxSpp)};
}

bool samePixels(const Image& a, const Image& b) {
  return a.pixels.size() == b.pixels.size() &&
         std::memcmp(a.pixels.data(), b.pixels.data(), a.pixels.size() * sizeof(Color)) == 0;
}

TEST(Adaptive, SameImageForOneAndTwoThreadsInBothModels) {
  const std::string cornell = kScenes + "cornell_physical.json";
  const RenderResult one = testing::renderFile(cornell, physical("true"), 1);
  const RenderResult two = testing::renderFile(cornell, physical("true"), 2);
  // Extra samples were taken, and the same ones.
  EXPECT_GT(one.stats.rays.camera, 48u * 48u * kPasses + 200);
  EXPECT_EQ(one.stats.rays.camera, two.stats.rays.camera);
  EXPECT_TRUE(samePixels(one.image, two.image));
  // The classic model's progressive passes (new camera samples on the same maps).
  const std::vector<std::string> classic = {"camera.width=40", "camera.height=40", "camera.spp=2",
                                            "photons.shadow=20000", "photons.indirect=20000", "photons.passes=4",
                                            "render.adaptive=true", "render.adaptive_threshold=1"};
  const std::string indirect = kScenes + "fig13_cornell_indirect.json";
  const RenderResult c1 = testing::renderFile(indirect, classic, 1), c2 = testing::renderFile(indirect, classic, 2);
  EXPECT_GT(c1.stats.rays.camera, 40u * 40u * 2 * 4);
  EXPECT_EQ(c1.stats.rays.camera, c2.stats.rays.camera);
  EXPECT_TRUE(samePixels(c1.image, c2.image));
}

TEST(Adaptive, SppViewCountsEverySampleWithinTheCap) {
  const std::string cornell = kScenes + "cornell_physical.json";
  const RenderResult r = testing::renderFile(cornell, physical("true"), 2, "spp");
  ASSERT_EQ(r.image.width, 48);
  double total = 0.0;
  float lo = 1e9f, hi = 0.0f;
  for (const Color& c : r.image.pixels) {
    EXPECT_EQ(c.r, c.g);
    total += c.r;
    lo = std::min(lo, c.r);
    hi = std::max(hi, c.r);
  }
  // Every camera ray is a sample the view counts.
  EXPECT_EQ(uint64_t(total), r.stats.rays.camera);
  // Two uniform passes, then at most kMaxSpp a pass; some pixel reached the cap each pass.
  EXPECT_EQ(lo, float(kPasses));
  EXPECT_EQ(hi, float(2 + (kPasses - 2) * kMaxSpp));
  // Off: every pixel took one sample a pass, and the beauty is uniform sampling's.
  const RenderResult off = testing::renderFile(cornell, physical("false"), 2, "spp");
  for (const Color& c : off.image.pixels) EXPECT_EQ(c.r, float(kPasses));
  std::vector<std::string> unset = physical("false");
  unset.erase(unset.begin() + 5);
  EXPECT_TRUE(samePixels(testing::renderFile(cornell, physical("false"), 2).image,
                         testing::renderFile(cornell, unset, 2).image));
}

// Two seeds' renders differ by twice one render's variance: their RMS difference over
// sqrt(2) is the noise each estimate claims (the default threshold, 8 passes).
TEST(Adaptive, EstimateMatchesTheNoiseBetweenSeeds) {
  const std::string cornell = kScenes + "cornell_physical.json";
  std::vector<std::string> o = {"camera.width=64", "camera.height=64", "photons.global=20000",
                                "photons.caustic=20000", "photons.passes=8", "render.adaptive=true"};
  const RenderResult a = testing::renderFile(cornell, o, 2);
  o.push_back("render.seed=2");
  const RenderResult b = testing::renderFile(cornell, o, 2);
  double squares = 0.0;
  for (size_t i = 0; i < a.image.pixels.size(); ++i) {
    for (int c = 0; c < 3; ++c) squares += std::pow(double(a.image.pixels[i][c]) - b.image.pixels[i][c], 2);
  }
  const double noise = std::sqrt(squares / (2.0 * 3.0 * a.image.pixels.size()));
  const double estimate = 0.5 * (a.stats.error.noiseRmse + b.stats.error.noiseRmse);
  std::printf("estimate %.5f, noise between seeds %.5f (x%.3f)\n", estimate, noise, estimate / noise);
  EXPECT_GT(a.stats.rays.camera, 64u * 64u * 8u);
  EXPECT_NEAR(estimate / noise, 1.0, 0.25);
}

}  // namespace
}  // namespace penumbra
