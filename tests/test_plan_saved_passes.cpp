// The passes file: what is saved is what is loaded, bit for bit (the spread's moments
// continue exactly where they stopped; a sum's coverage comes back with it); any
// other identity, pass count or size, and every truncation, is refused with its reason.
#include "plan/saved_passes.h"
#include "support/scratch_dir.h"
#include <gtest/gtest.h>
#include <cstring>
#include <fstream>
#include <iterator>

namespace penumbra {
namespace {

using testing::ScratchDir;

Image pass(int w, int h, float base) {
  Image im(w, h);
  for (size_t i = 0; i < im.pixels.size(); ++i) im.pixels[i] = Color(base + 0.1f * float(i), base * 0.5f, 1.0f / (1.0f + float(i)));
  return im;
}

// Three passes summed as the frame sums them, with their spread.
SavedPasses threePasses() {
  SavedPasses s;
  s.identity = "scene a.json\nview beauty";
  s.passes = 12;
  PassSpread spread;
  for (int p = 0; p < 3; ++p) {
    const Image image = pass(5, 3, 0.3f * float(p + 1));
    spread.add(image, p);
    if (p == 0) s.sum = image;
    else for (size_t i = 0; i < image.pixels.size(); ++i) s.sum.pixels[i] += image.pixels[i];
  }
  s.done = 3;
  s.seconds = 12.5;
  s.spread = spread.moments();
  s.emitted[MapKind::Global] = 30000;
  s.stored[MapKind::Caustic] = 2711;
  s.rays.camera = 45;
  s.rays.nonfiniteSamples = 1;
  s.gatherRadius[MapKind::Global] = 0.0625f;
  return s;
}

bool sameImage(const Image& a, const Image& b) {
  return a.width == b.width && a.height == b.height && a.pixels.size() == b.pixels.size() &&
         std::memcmp(a.pixels.data(), b.pixels.data(), a.pixels.size() * sizeof(Color)) == 0;
}

TEST(SavedPasses, WhatIsSavedIsLoadedBitForBitAndContinuesTheSpread) {
  const ScratchDir dir;
  const std::string path = savedPassesPath((dir / "out.exr").string());
  EXPECT_EQ(path, (dir / "out.exr.passes").string());
  EXPECT_EQ(savedPassesPath("a.exr", "depth"), "a.exr.depth.passes");
  const SavedPasses s = threePasses();
  const uint64_t bytes = savePasses(path, s);
  EXPECT_EQ(bytes, std::filesystem::file_size(path));
  std::string why;
  const std::optional<SavedPasses> back = loadPasses(path, s.identity, 12, 5, 3, why);
  ASSERT_TRUE(back) << why;
  EXPECT_EQ(back->done, 3);
  EXPECT_EQ(back->seconds, 12.5);
  EXPECT_TRUE(sameImage(back->sum, s.sum));
  EXPECT_EQ(back->emitted, s.emitted);
  EXPECT_EQ(back->stored, s.stored);
  EXPECT_EQ(back->rays.camera, 45u);
  EXPECT_EQ(back->rays.nonfiniteSamples, 1u);
  EXPECT_EQ(back->gatherRadius, s.gatherRadius);
  // The fourth pass onto the loaded spread: the estimate a run that never stopped has.
  PassSpread whole, resumed;
  whole.restore(s.spread);
  resumed.restore(back->spread);
  const Image fourth = pass(5, 3, 1.7f);
  whole.add(fourth, 3);
  resumed.add(fourth, 3);
  const ErrorEstimate a = whole.estimate(), b = resumed.estimate();
  EXPECT_EQ(a.noiseRmse, b.noiseRmse);
  EXPECT_EQ(a.biasRmse, b.biasRmse);
  EXPECT_EQ(a.lightingNoiseRmse, b.lightingNoiseRmse);
  EXPECT_TRUE(sameImage(whole.bias(), resumed.bias()));
  EXPECT_EQ(a.biasHalf, b.biasHalf);
  EXPECT_GT(b.biasHalf, 0);
  EXPECT_TRUE(sameImage(whole.standardError(), resumed.standardError()));
}

TEST(SavedPasses, ASumsCoverageIsLoadedBitForBit) {
  const ScratchDir dir;
  const std::string path = (dir / "out.exr.passes").string();
  SavedPasses s = threePasses();
  s.sum.coverage = {0.0f, 1.0f, 2.5f, 0.125f, 3.0f, 1.0f, 0.0f, 0.75f, 1.5f, 2.0f, 0.0f, 3.0f, 1.0f, 0.5f, 2.25f};
  savePasses(path, s);
  std::string why;
  const std::optional<SavedPasses> back = loadPasses(path, s.identity, 12, 5, 3, why);
  ASSERT_TRUE(back) << why;
  EXPECT_TRUE(sameImage(back->sum, s.sum));
  EXPECT_EQ(back->sum.coverage, s.sum.coverage);
  EXPECT_TRUE(back->spread.even.coverage.empty()) << "an image without coverage stays without";
}

TEST(SavedPasses, AnotherJobPassCountOrSizeIsRefusedWithItsReason) {
  const ScratchDir dir;
  const std::string path = (dir / "out.exr.passes").string();
  const SavedPasses s = threePasses();
  savePasses(path, s);
  std::string why;
  EXPECT_FALSE(loadPasses(path, s.identity + " ", 12, 5, 3, why));
  EXPECT_EQ(why, "saved by another job or setting");
  EXPECT_FALSE(loadPasses(path, s.identity, 16, 5, 3, why));
  EXPECT_NE(why.find("saved for 12 passes of 5x3 after 3"), std::string::npos) << why;
  EXPECT_FALSE(loadPasses(path, s.identity, 12, 3, 5, why));
  EXPECT_NE(why.find("not this frame's 12 of 3x5"), std::string::npos) << why;
  EXPECT_FALSE(loadPasses((dir / "missing.passes").string(), s.identity, 12, 5, 3, why));
  EXPECT_EQ(why, "") << "no file is no note";
}

TEST(SavedPasses, EveryTruncationIsRefused) {
  const ScratchDir dir;
  const std::string path = (dir / "out.exr.passes").string();
  const SavedPasses s = threePasses();
  const uint64_t bytes = savePasses(path, s);
  std::ifstream in(path, std::ios::binary);
  const std::string whole((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
  ASSERT_EQ(whole.size(), bytes);
  for (size_t keep = 0; keep < bytes; keep += keep < 64 ? 1 : 37) {
    std::ofstream(path, std::ios::binary | std::ios::trunc) << whole.substr(0, keep);
    std::string why;
    EXPECT_FALSE(loadPasses(path, s.identity, 12, 5, 3, why)) << keep;
    EXPECT_FALSE(why.empty()) << keep;
  }
}

}  // namespace
}  // namespace penumbra
