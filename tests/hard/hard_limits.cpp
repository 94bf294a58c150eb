// Hard cases, class "limits": zero photons, k larger than the map, max_depth 0 and
// 64, and extreme light intensities (1e-20 .. 1e20, and near the float range).
#include "hard/hard_support.h"

using namespace penumbra;
using namespace penumbra::hard;

namespace {

const std::string kSpheres = R"(,
    {"type": "sphere", "material": "mirror", "center": [0.5, 0.3, -0.5], "radius": 0.3},
    {"type": "sphere", "material": "glass", "center": [-0.4, 0.3, 0.2], "radius": 0.3})";

// No photons at all, in every way a scene can have none. Each renders, without NaN,
// within the room's bound; with no map the physical image is the direct light
// alone, so it equals the render with the maps switched off the ordinary way.
TEST(HardLimits, ZeroPhotonsRender) {
  RenderResult direct = renderJson(roomJson("physical", kSpheres),
                                   {"photons.global=0", "photons.caustic=0"});
  expectSane(direct, roomBound("physical"), "physical, no maps");
  ASSERT_GT(meanPixel(direct.image), 0.01);
  const std::vector<std::vector<std::string>> empty = {
      {"photons.global=0", "photons.caustic=0", "photons.gate=on", "photons.shadow=0"},
      {"photons.max_bounces=0"},                                       // maps emitted but empty
      {"photons.global=0", "photons.caustic=0", "photons.passes=3"},   // radius from no photons
      {"photons.global=0", "photons.caustic=0", "photons.passes=3", "photons.radius=0.1"},
  };
  // 3 passes draw the camera samples of one pass at 3 spp, and the same light samples.
  const RenderResult threeSpp =
      renderJson(roomJson("physical", kSpheres), {"photons.global=0", "photons.caustic=0", "camera.spp=3"});
  for (const auto& o : empty) {
    std::string what = "physical";
    for (const auto& s : o) what += " " + s;
    RenderResult r = renderJson(roomJson("physical", kSpheres), o);
    expectSane(r, roomBound("physical"), what);
    // Same direct light, nothing added (direct light does not depend on the maps):
    // identical for one pass; for 3 passes the 3-spp image up to the float rounding of
    // the passes' mean.
    const bool passes = r.stats.passes > 1;
    EXPECT_LE(rmse(r.image, passes ? threeSpp.image : direct.image), passes ? 1e-5 : 1e-6) << what;
  }
  for (const std::vector<std::string>& o : {std::vector<std::string>{"photons.gate=on", "photons.shadow=0"},
                                           {"photons.indirect=0"},
                                           {"photons.indirect=1", "photons.estimator=density"}}) {
    RenderResult r = renderJson(roomJson("classic", kSpheres), o);
    expectSane(r, roomBound("classic"), "classic " + o[0]);
    EXPECT_GT(meanPixel(r.image), 0.01);
  }
}

// k larger than the map: the estimate uses every photon there is, so it equals the
// estimate with k = the map's size exactly (the same photons, sorted the same way;
// 1e-6 RMSE for summation order). The maps are kept to a few hundred photons.
// One model's two maps: render with both k keys at 10000, then with each k equal to
// the photons its map stored (`stored` reads those two counts from the stats).
void expectKBeyondTheMapIsTheMap(const std::string& model, const std::vector<std::string>& base,
                                 const std::string& k1, const std::string& k2,
                                 std::pair<uint64_t, uint64_t> (*stored)(const RenderStats&)) {
  auto with = [&](std::vector<std::string> more) {
    std::vector<std::string> o = base;
    o.insert(o.end(), more.begin(), more.end());
    return o;
  };
  RenderResult big = renderJson(roomJson(model, kSpheres), with({k1 + "=10000", k2 + "=10000"}));
  expectSane(big, roomBound(model), model + " k 10000");
  const auto [n1, n2] = stored(big.stats);
  ASSERT_GT(n1, 0u);
  ASSERT_GT(n2, 0u);
  ASSERT_LT(n1, 10000u);
  ASSERT_LT(n2, 10000u);
  RenderResult all = renderJson(roomJson(model, kSpheres),
                                with({k1 + "=" + std::to_string(n1), k2 + "=" + std::to_string(n2)}));
  EXPECT_LE(rmse(big.image, all.image), 1e-6) << model;
}

TEST(HardLimits, KLargerThanTheMapEqualsKEqualsTheMap) {
  expectKBeyondTheMapIsTheMap(
      "physical", {"photons.global=150", "photons.caustic=100", "photons.max_bounces=2"},
      "photons.k_global", "photons.k_caustic",
      [](const RenderStats& s) { return std::pair<uint64_t, uint64_t>(s.stored[MapKind::Global], s.stored[MapKind::Caustic]); });
  // Classic: the indirect map and the gate's shadow map.
  expectKBeyondTheMapIsTheMap(
      "classic", {"photons.indirect=200", "photons.shadow=300", "photons.gate=on"},
      "photons.k_indirect", "photons.k_shadow",
      [](const RenderStats& s) { return std::pair<uint64_t, uint64_t>(s.stored[MapKind::Indirect], s.stored[MapKind::Shadow]); });
}

// max_depth 0: no mirror or glass ray at all, so the physical mirror (kr = 1) and
// glass spheres are black where the camera sees them; max_depth 64 with min_weight 0:
// sane, within the bound for depth 64, and the extra depth only adds light (the same
// photon maps: they do not depend on max_depth) and little of it (the series has
// converged by depth 8: < 5% of the mean).
TEST(HardLimits, MaxDepthZeroAndSixtyFour) {
  for (const std::string model : {"physical", "classic"}) {
    RenderResult d0 = renderJson(roomJson(model, kSpheres), {"render.max_depth=0"});
    RenderResult d8 = renderJson(roomJson(model, kSpheres), {"render.max_depth=8", "render.min_weight=0"});
    RenderResult d64 = renderJson(roomJson(model, kSpheres), {"render.max_depth=64", "render.min_weight=0"});
    expectSane(d0, roomBound(model, 0), model + " depth 0");
    expectSane(d64, roomBound(model, 64), model + " depth 64");
    if (model == "physical") {
      // The two spheres (about 40 pixels each) are black at depth 0, lit at depth 8.
      int blackened = 0;
      for (size_t i = 0; i < d0.image.pixels.size(); ++i)
        if (maxComponent(d0.image.pixels[i]) == 0.0f && maxComponent(d8.image.pixels[i]) > 0.0f) ++blackened;
      EXPECT_GE(blackened, 40) << "depth 0 still followed mirror or glass rays";
    }
    // 1e-4: the ray budget and summation order move the mean by ~1e-5 (measured).
    EXPECT_GE(meanPixel(d64.image), meanPixel(d8.image) * (1 - 1e-4)) << model;
    EXPECT_LE(meanPixel(d64.image), meanPixel(d8.image) * 1.05) << model;
    EXPECT_LE(meanPixel(d0.image), meanPixel(d8.image)) << model;
  }
}

// Extreme intensities. A point light of intensity I in the opaque room (no ambient):
// the image is linear in I, so image(I) / I must equal image(1) per pixel (to the
// precision below, + 1e-6 of the brightest pixel) for I = 1e-20 and 1e20: nothing
// underflows, overflows or is thresholded absolutely.
// Bound: rho/pi I / d^2 / (1 - rho) (physical; d = 0.5 light to ceiling),
// (D + 1) rho I / d^2 (classic).
std::string pointLight(double intensity) {
  return "lights=[{\"type\": \"point\", \"position\": [0, 1.5, 0], \"intensity\": " + num(intensity) + "}]";
}
double pointBound(const std::string& model, double intensity) {
  const double rho = 0.73;
  return model == "physical" ? rho / 3.14159265 * intensity / 0.25 / (1 - rho)
                             : 9 * rho * intensity / 0.25;
}

TEST(HardLimits, ExtremeIntensitiesScaleLinearly) {
  const std::string box = R"(,
    {"type": "box", "material": "white", "min": [-0.6, 0, -0.6], "max": [0, 0.7, 0]})";
  for (const std::string model : {"physical", "classic"}) {
    RenderResult one = renderJson(roomJson(model, box), {pointLight(1), "render.ambient=0"});
    expectSane(one, pointBound(model, 1), model + " I = 1");
    const float peak = maxPixel(one.image);
    ASSERT_GT(peak, 0.0f);
    // Physical photons carry shared-exponent power, each channel within 2^-8 of its
    // value; scaled by 1e20 (not a power of 2) they round differently, so the
    // estimates agree to 2^-8 relative. Classic renders hold no photon: 1e-4.
    const float relTol = model == "physical" ? 1.0f / 256 : 1e-4f;
    for (double intensity : {1e-20, 1e20}) {
      const std::string what = model + " I = " + num(intensity);
      RenderResult r = renderJson(roomJson(model, box), {pointLight(intensity), "render.ambient=0"});
      expectSane(r, pointBound(model, intensity), what);
      int off = 0;
      for (size_t i = 0; i < r.image.pixels.size(); ++i) {
        const Color scaled = Color(glm::dvec3(r.image.pixels[i]) / intensity);
        const Color want = one.image.pixels[i];
        if (maxComponent(glm::abs(scaled - want)) > relTol * maxComponent(want) + 1e-6f * peak) ++off;
      }
      Image scaledImage = r.image;
      for (Color& px : scaledImage.pixels) px = Color(glm::dvec3(px) / intensity);
      EXPECT_EQ(off, 0) << what << ": pixels not I x the I = 1 image:" << worstPixels(one.image, scaledImage);
    }
    // Quad light radiance 1e-20 and 1e20: sane (bounded by L), and not black.
    for (double radiance : {1e-20, 1e20}) {
      RenderResult r = renderJson(roomJson(model, box), {"lights[0].radiance=" + num(radiance), "render.ambient=0"});
      // classicRoomBound without its ambient: (8 + 1) x k_d L A / d^2 with A / d^2 = 1.
      const double bound = model == "physical" ? radiance * (1 + 1e-5) : 9 * 0.73 * radiance;
      expectSane(r, bound, model + " L = " + num(radiance));
      EXPECT_GT(meanPixel(r.image), 1e-3 * radiance) << model;
    }
    // Near the float range the loader may refuse (a range check), or must render a
    // sane image: I = 1e36 keeps I / d^2 and photon powers (4 pi I / N) finite.
    expectRefusedOrSane([&] { return renderJson(roomJson(model, box), {pointLight(1e36), "render.ambient=0"}); },
                        pointBound(model, 1e36), model + " I = 1e36");
  }
}

}  // namespace
