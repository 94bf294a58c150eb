// The render plan against forced renders: for every shipped scene, forcing on every
// pass the plan turned off gives a byte-identical image (it had nothing to add),
// skipped passes cost no photons or rays, and the approximations the plan may pick
// (the gate, precomputed lookups) stay within the noise of a second seed; and the
// reuse keys change exactly with the inputs that matter.
#include "plan/pipeline.h"
#include "plan/render_plan.h"
#include "plan/reuse_key.h"
#include "io/image_compare.h"
#include "io/scene_loader.h"
#include <gtest/gtest.h>
#include <filesystem>

namespace penumbra {
namespace {

namespace fs = std::filesystem;
const std::string kCornell = std::string(PENUMBRA_SOURCE_DIR) + "/scenes/cornell_physical.json";

std::vector<std::string> shippedScenes() {
  std::vector<std::string> out;
  for (const auto& e : fs::directory_iterator(fs::path(PENUMBRA_SOURCE_DIR) / "scenes")) {
    // teapot_1m and soft_shadows_dense hold 1M-triangle teapots, for benchmarks: the
    // tessellation alone makes every render slow, and they have no pass fig05 and
    // soft_shadows lack.
    const std::string stem = e.path().stem().string();
    if (e.path().extension() == ".json" && stem != "teapot_1m" && stem != "soft_shadows_dense") {
      out.push_back(e.path().string());
    }
  }
  std::sort(out.begin(), out.end());
  return out;
}

// Small and quick; budgets cut so the photon passes that do run stay short.
std::vector<std::string> quick(uint64_t seed = 1) {
  return {"camera.width=48", "camera.height=32", "camera.spp=1", "photons.shadow=20000",
          "photons.indirect=20000", "photons.global=20000", "photons.caustic=20000", "photons.volume=20000",
          "render.seed=" + std::to_string(seed)};
}

RenderResult render(const std::string& scene, const PlanOverrides& plan, uint64_t seed = 1) {
  RenderRequest r;
  r.scenePath = scene;
  r.overrides = quick(seed);
  r.session.threads = 2;
  r.session.plan = plan;
  return runRender(r);
}

// Every pass the automatic plan left off, except the two that trade exactness for
// speed by design (the gate's verdicts replace shadow rays; precomputed lookups
// replace gathers): those are checked against the noise below.
// Shadow rays forced on where render.shadows is false add the shadows the scene
// asked not to have: the plan says such an override changes the image (checked).
PlanOverrides everyOffPassOn(const Scene& scene, const RenderPlan& plan, bool approximations) {
  PlanOverrides o;
  for (size_t i = 0; i < kPassCount; ++i) {
    const Pass p = static_cast<Pass>(i);
    const bool approx = p == Pass::Gate || p == Pass::Precompute;
    if (!plan.passes[i].on && (approximations || !approx)) o.enable.push_back(p);
  }
  const RenderPlan forced = makePlan(scene, plan.aov, o);
  PlanOverrides unchanged;
  for (Pass p : o.enable) {
    const bool expected = p == Pass::Gate || p == Pass::Precompute || (p == Pass::ShadowRays && !scene.render.shadows);
    EXPECT_EQ(forced[p].changesImage, expected) << passName(p);
    const bool approx = p == Pass::Gate || p == Pass::Precompute;
    if (!forced[p].changesImage || (approximations && approx)) unchanged.enable.push_back(p);
  }
  return unchanged;
}

class PlanScenes : public ::testing::TestWithParam<std::string> {};

TEST_P(PlanScenes, ForcingOnWhatThePlanSkippedChangesNoByte) {
  Scene scene = loadScene(GetParam(), quick());
  const Aov aov = parseAov(scene.render.aov);
  const RenderPlan plan = makePlan(scene, aov);
  const RenderResult automatic = render(GetParam(), {});
  const RenderResult forced = render(GetParam(), everyOffPassOn(scene, plan, false));
  ASSERT_EQ(automatic.image.pixels.size(), forced.image.pixels.size());
  EXPECT_EQ(compareImages(forced.image, automatic.image).maxError, 0.0) << GetParam();
  // Skipped passes cost nothing: no photons or rays of that kind.
  const RenderStats& s = automatic.stats;
  if (!plan[Pass::Gate].on) { EXPECT_EQ(s.emitted[MapKind::Shadow] + s.rays.gateQueries, 0u); }
  if (!plan[Pass::IndirectPhotons].on) { EXPECT_EQ(s.emitted[MapKind::Indirect], 0u); }
  if (!plan[Pass::GlobalPhotons].on) { EXPECT_EQ(s.emitted[MapKind::Global], 0u); }
  if (!plan[Pass::CausticPhotons].on) { EXPECT_EQ(s.emitted[MapKind::Caustic], 0u); }
  if (!plan[Pass::ShadowRays].on) { EXPECT_EQ(s.rays.shadow, 0u); }
  if (!plan[Pass::Reflection].on) { EXPECT_EQ(s.rays.reflection, 0u); }
  if (!plan[Pass::Refraction].on) { EXPECT_EQ(s.rays.refraction, 0u); }
  if (!plan[Pass::Precompute].on) { EXPECT_EQ(s.cacheRecords, 0u); }
}

// The gate and precomputed lookups are approximations: forced on where the plan
// left them off, the image may move, but by less than the Monte Carlo noise of the
// render itself (RMSE against the same render with another seed).
TEST_P(PlanScenes, ApproximationsThePlanSkippedStayWithinTheNoise) {
  Scene scene = loadScene(GetParam(), quick());
  const RenderPlan plan = makePlan(scene, parseAov(scene.render.aov));
  if (plan[Pass::Gate].on && plan[Pass::Precompute].on) GTEST_SKIP() << "nothing skipped";
  const RenderResult automatic = render(GetParam(), {});
  const RenderResult forced = render(GetParam(), everyOffPassOn(scene, plan, true));
  const RenderResult other = render(GetParam(), {}, 2);
  const double change = compareImages(forced.image, automatic.image).rmse;
  const double noise = compareImages(other.image, automatic.image).rmse;
  // Noise-free views (no jitter at 1 spp, no photons): the change must be tiny instead.
  EXPECT_LE(change, std::max(noise, 0.01)) << GetParam() << ": noise " << noise;
}

INSTANTIATE_TEST_SUITE_P(Shipped, PlanScenes, ::testing::ValuesIn(shippedScenes()),
                         [](const ::testing::TestParamInfo<std::string>& tp) {
                           return fs::path(tp.param).stem().string();
                         });

TEST(Plan, ReasonsNameWhyAPassIsOff) {
  Scene scene;
  scene.lights.push_back(Light{});
  scene.materials.push_back(Material{});
  scene.photons.estimator = IndirectEstimator::Density;
  scene.photons.indirectPhotons = 1000;
  const RenderPlan plan = makePlan(scene, Aov::Beauty);
  EXPECT_FALSE(plan[Pass::IndirectPhotons].on);
  EXPECT_EQ(plan[Pass::IndirectPhotons].reason, "no surface can bounce a photon: every p_r and p_t is 0");
  EXPECT_EQ(plan[Pass::Refraction].reason, "no transparent material");
  const RenderPlan depth = makePlan(scene, Aov::Depth);
  EXPECT_FALSE(depth[Pass::ShadowRays].on);
  EXPECT_FALSE(depth[Pass::Textures].on);
  const RenderPlan forced = makePlan(scene, Aov::Beauty, {{Pass::IndirectPhotons}, {Pass::ShadowRays}});
  EXPECT_TRUE(forced[Pass::IndirectPhotons].on);
  EXPECT_EQ(forced[Pass::IndirectPhotons].budget, 1000u);
  EXPECT_FALSE(forced[Pass::ShadowRays].on);
  EXPECT_TRUE(forced[Pass::ShadowRays].changesImage);
}

TEST(Plan, LookupAutoPrecomputesWhereExactGathersWouldDominate) {
  // A user's model under a point light with a 200k-photon indirect map and no
  // photons.lookup: at 640 x 480 the exact gathers cost far more than one query per
  // point plus the cells; a 16 x 16 render has fewer points than cells: exact.
  Scene scene;
  scene.lights.push_back(Light{});
  Material bounce;
  bounce.pR = 0.5f;
  scene.materials.push_back(bounce);
  scene.photons.indirectPhotons = 200000;
  ASSERT_EQ(scene.photons.lookup, PhotonLookup::Auto);
  const RenderPlan big = makePlan(scene, Aov::Beauty);
  ASSERT_TRUE(big[Pass::IndirectPhotons].on);
  EXPECT_TRUE(big[Pass::Precompute].on);
  EXPECT_EQ(big[Pass::Precompute].reason.rfind("auto: precomputed: exact gathers ~", 0), 0u) << big[Pass::Precompute].reason;
  scene.camera.width = scene.camera.height = 16;
  const RenderPlan small = makePlan(scene, Aov::Beauty);
  EXPECT_FALSE(small[Pass::Precompute].on);
  EXPECT_EQ(small[Pass::Precompute].reason.rfind("auto: exact", 0), 0u) << small[Pass::Precompute].reason;
  scene.camera.width = 640;
  scene.camera.height = 480;
  scene.photons.lookup = PhotonLookup::Exact;
  EXPECT_EQ(makePlan(scene, Aov::Beauty)[Pass::Precompute].reason, "photons.lookup is exact");
}

// The keys decide what runs share: each photon input changes the photon key,
// camera and gather settings keep it, and only geometry inputs change the other.
TEST(ReuseKey, ChangesExactlyWithTheInputsThatMatter) {
  const std::vector<std::string> base = {"camera.width=32"};
  const ReuseKeys keys = reuseKeys(kCornell, base);
  auto with = [&](const std::string& o) {
    std::vector<std::string> v = base;
    v.push_back(o);
    return reuseKeys(kCornell, v);
  };
  for (const char* same : {"camera.position=[0,1,3]", "camera.spp=16", "camera.fov=40", "render.max_depth=3",
                           "photons.k_global=7", "photons.global=1000", "photons.caustic=10",
                           "photons.gate=true", "photons.lookup=\"precomputed\"", "name=\"other\""}) {
    const ReuseKeys k = with(same);
    EXPECT_EQ(k.photons, keys.photons) << same;
    EXPECT_EQ(k.geometry, keys.geometry) << same;
  }
  for (const char* photon : {"render.seed=2", "photons.max_bounces=3", "photons.passes=2",
                             "photons.sampling=\"uniform\""}) {
    const ReuseKeys k = with(photon);
    EXPECT_NE(k.photons, keys.photons) << photon;
    EXPECT_EQ(k.geometry, keys.geometry) << photon;
  }
  for (const char* geometry : {"objects[5].radius=0.3", "materials.white.diffuse=0.5", "lights[0].intensity=2",
                               "render.model=\"classic\""}) {
    const ReuseKeys k = with(geometry);
    EXPECT_NE(k.photons, keys.photons) << geometry;
    EXPECT_NE(k.geometry, keys.geometry) << geometry;
  }
}

}  // namespace
}  // namespace penumbra
