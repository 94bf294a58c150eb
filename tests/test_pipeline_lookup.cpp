// photons.lookup = precomputed against the exact k-nearest path on gallery scenes:
// the image differs from exact by less than half the exact path's own noise (its
// RMSE against another seed), and it is identical for 1 and 2 threads.
#include "plan/pipeline.h"
#include <OpenImageIO/imagebufalgo.h>
#include <gtest/gtest.h>
#include <cstdio>
#include <cstring>

using namespace penumbra;

namespace {

const std::string kSource = PENUMBRA_SOURCE_DIR;

struct Case {
  std::string scene;
  std::vector<std::string> overrides;  // smaller renders, so the suite stays quick
  double maxRmse;                      // absolute bound on RMSE(precomputed, exact)
};

RenderResult render(const Case& c, std::vector<std::string> extra, int threads = 0) {
  RenderRequest req;
  req.scenePath = kSource + "/scenes/" + c.scene;
  req.overrides = c.overrides;
  req.overrides.insert(req.overrides.end(), extra.begin(), extra.end());
  req.session.threads = threads;
  return runRender(req);
}

double rmse(const Image& a, const Image& b) {
  auto buf = [](const Image& im) {
    OIIO::ImageBuf out(OIIO::ImageSpec(im.width, im.height, 3, OIIO::TypeDesc::FLOAT));
    out.set_pixels(OIIO::ROI::All(), OIIO::TypeDesc::FLOAT, im.pixels.data());
    return out;
  };
  return OIIO::ImageBufAlgo::compare(buf(a), buf(b), 1.0f, 1.0f).rms_error;
}

bool samePixels(const Image& a, const Image& b) {
  return a.pixels.size() == b.pixels.size() &&
         std::memcmp(a.pixels.data(), b.pixels.data(), a.pixels.size() * sizeof(Color)) == 0;
}

class PrecomputedLookup : public ::testing::TestWithParam<Case> {};

TEST_P(PrecomputedLookup, WithinTheExactPathsOwnNoise) {
  const Case& c = GetParam();
  RenderResult exact = render(c, {"photons.lookup=exact"});
  RenderResult other = render(c, {"photons.lookup=exact", "render.seed=99"});
  RenderResult pre = render(c, {"photons.lookup=precomputed"});
  ASSERT_GT(pre.stats.cacheRecords, 0u);
  EXPECT_GT(pre.stats.rays.cacheLookups, 0u);
  // Fallbacks to a cell computed on first use are rare: a few points without a cell
  // of the light map nearby (2% on the showcase, with or without the gate's cells).
  EXPECT_LE(pre.stats.rays.cacheFallbacks * 25, pre.stats.rays.cacheLookups);
  for (const Color& p : pre.image.pixels) ASSERT_TRUE(isFinite(p));
  const double error = rmse(pre.image, exact.image), noise = rmse(other.image, exact.image);
  RecordProperty("rmse", std::to_string(error));
  RecordProperty("noise", std::to_string(noise));
  std::printf("%s: RMSE(precomputed, exact) %.5f, RMSE(exact, other seed) %.5f\n", c.scene.c_str(),
              error, noise);
  EXPECT_LE(error, c.maxRmse) << c.scene;
  EXPECT_LE(error, std::max(0.5 * noise, 2e-4)) << c.scene << ": noise " << noise;
}

TEST_P(PrecomputedLookup, IdenticalForOneAndTwoThreads) {
  const Case& c = GetParam();
  RenderResult one = render(c, {"photons.lookup=precomputed"}, 1);
  RenderResult two = render(c, {"photons.lookup=precomputed"}, 2);
  EXPECT_EQ(one.stats.cacheRecords, two.stats.cacheRecords);
  EXPECT_EQ(one.stats.rays.shadow, two.stats.rays.shadow);
  EXPECT_TRUE(samePixels(one.image, two.image)) << c.scene;
}

// The gate on: at this size auto would turn it off, and the verdicts are under test.
const std::vector<std::string> kSmall = {"camera.width=160", "camera.height=100", "camera.spp=2",
                                         "photons.gate=on"};

std::vector<std::string> with(std::vector<std::string> a, const std::vector<std::string>& b) {
  a.insert(a.end(), b.begin(), b.end());
  return a;
}

INSTANTIATE_TEST_SUITE_P(
    Gallery, PrecomputedLookup,
    ::testing::Values(
        // Indirect map (classic estimator) and the gate.
        Case{"fig14_cornell.json", with(kSmall, {"photons.shadow=400000", "photons.indirect=400000"}), 0.01},
        // The gate alone: shadow rays make the image, the cache only skips some.
        Case{"fig11_gate_shadows.json", with(kSmall, {"photons.shadow=400000"}), 0.002},
        // Glass in the box: behind glass the vote is always a ray.
        Case{"fig07_glass_in_box.json", with(kSmall, {"photons.shadow=400000"}), 0.002},
        // The showcase: two lights, glass, mirrors, k = 200.
        Case{"showcase.json", with(kSmall, {"photons.shadow=500000", "photons.indirect=500000"}), 0.01},
        // Area lights: one verdict per light decides 16 samples.
        Case{"soft_shadows.json", with(kSmall, {"photons.shadow=500000"}), 0.002},
        // Physical model: the global map's irradiance and the gate (glass blocks).
        Case{"cornell_physical.json", with(kSmall, {"camera.spp=1", "photons.passes=1", "photons.gate=true"}), 0.03}),
    [](const auto& tp) {
      std::string n = tp.param.scene.substr(0, tp.param.scene.find('.'));
      return n;
    });

}  // namespace
