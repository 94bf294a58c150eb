// The resource estimate against what renders actually store: an upper bound on the
// photon maps within 2x on the Cornell box, a closed many-bounce box and the
// physical model; the lookup cache within 0.8-2x; gallery scenes always admitted;
// sizes parsed; long jobs told.
#include "plan/job_admission.h"
#include "plan/cost_model.h"
#include "plan/memory_limit.h"
#include "plan/pipeline.h"
#include "core/error.h"
#include "io/scene_loader.h"
#include "support/scratch_dir.h"
#include "support/render_file.h"
#include <gtest/gtest.h>
#include <filesystem>
#include <fstream>

using namespace penumbra;
namespace fs = std::filesystem;

namespace {

const std::string kScenes = std::string(PENUMBRA_SOURCE_DIR) + "/scenes/";

RenderResult render(const std::string& scene, std::vector<std::string> overrides) {
  return penumbra::testing::renderFile(scene, std::move(overrides));
}

void expectBounds(const RenderResult& r, const char* what) {
  const double actual = double(r.stats.photonMapBytes), estimate = r.estimate.photonBytes;
  ASSERT_GT(actual, 0.0) << what;
  EXPECT_GE(estimate, actual) << what << ": the estimate must be an upper bound";
  EXPECT_LE(estimate, 2.0 * actual) << what << ": the estimate is too pessimistic";
}

// A closed box lit from inside: no photon escapes, so every path runs until its
// roulette (p_r 0.9 -> ~10 stores) or the bounce cap ends it.
std::string closedBox(const fs::path& dir) {
  const fs::path path = dir / "closed_box.json";
  std::ofstream(path) << R"({"name": "closed_box",
    "camera": {"position": [0, 0, 0.5], "look_at": [0, 0, -1], "width": 16, "height": 16},
    "lights": [{"type": "point", "position": [0, 0.5, 0], "intensity": 1}],
    "materials": {"wall": {"diffuse": 0.9, "p_r": 0.9}},
    "objects": [{"type": "box", "min": [-1, -1, -1], "max": [1, 1, 1], "material": "wall"}],
    "photons": {"shadow": 0, "indirect": 200000, "max_bounces": 64}})";
  return path.string();
}

}  // namespace

TEST(ResourceEstimate, PhotonBytesBoundTheCornellBoxMaps) {
  const RenderResult r = render(kScenes + "fig14_cornell.json",
                                {"camera.width=32", "camera.height=32", "photons.gate=on",
                                 "photons.shadow=400000", "photons.indirect=400000"});
  ASSERT_GT(r.stats.stored[MapKind::Shadow], 0u);
  EXPECT_TRUE(r.estimate.rates.measured);  // 9 surfaces a line could cross: the pilot ran
  expectBounds(r, "fig14");
}

TEST(ResourceEstimate, PhotonBytesBoundAClosedBoxWithManyBounces) {
  const penumbra::testing::ScratchDir scratch;
  const fs::path& dir = scratch.path();
  const RenderResult r = render(closedBox(dir), {});
  expectBounds(r, "closed box");
  // The analytic bound alone (no pilot) is exact here up to noise: nothing escapes.
  const Scene scene = loadScene(closedBox(dir));
  EstimateOptions options;
  options.photons = photonPlanOf(makePlan(scene, Aov::Beauty), scene, false);
  const ResourceEstimate analytic = estimateResources(scene, options, analyticStoreRates(scene));
  EXPECT_GE(analytic.photonBytes, double(r.stats.photonMapBytes));
  EXPECT_LE(analytic.photonBytes, 1.1 * double(r.stats.photonMapBytes));
}

TEST(ResourceEstimate, PhotonBytesBoundThePhysicalMaps) {
  const RenderResult r = render(kScenes + "cornell_physical.json",
                                {"camera.width=16", "camera.height=16", "photons.passes=1"});
  expectBounds(r, "cornell_physical");
}

// The lookup cache's records follow its cells (a multiple of the gather radius):
// the estimate is within 0.8-2x of what the cache holds, with the gate's verdicts
// per stratum and split lines, and with the physical model's two caches.
void expectCacheNear(const RenderResult& r, const char* what) {
  const double actual = double(r.stats.cacheBytes), estimate = r.estimate.cacheBytes;
  ASSERT_GT(actual, 0.0) << what;
  EXPECT_GE(estimate, 0.8 * actual) << what << ": " << estimate << " estimated, " << actual << " held";
  EXPECT_LE(estimate, 2.0 * actual) << what << ": " << estimate << " estimated, " << actual << " held";
}

TEST(ResourceEstimate, LookupCacheBytesFollowItsCells) {
  expectCacheNear(render(kScenes + "fig14_cornell.json",
                         {"camera.width=32", "camera.height=32", "photons.gate=on", "photons.lookup=precomputed"}),
                  "fig14, indirect and gate cells");
  expectCacheNear(render(kScenes + "soft_shadows_physical.json", {"camera.width=32", "camera.height=20", "photons.gate=on"}),
                  "soft_shadows_physical, global and gate caches");
}

TEST(ResourceEstimate, EveryGallerySceneIsAdmittedWithRoomToSpare) {
  // The estimate must never refuse a documented scene on this 24 GiB machine.
  for (const auto& entry : fs::directory_iterator(kScenes)) {
    if (entry.path().extension() != ".json") continue;
    Scene scene = loadScene(entry.path().string());
    const RenderPlan plan = makePlan(scene, parseAov(scene.render.aov));
    Admission a = admitJob(scene, plan, 2, false, 16ull << 30);
    TraceScene tracer(scene);
    EXPECT_NO_THROW(confirmJob(a, scene, tracer, {})) << entry.path();
    EXPECT_LT(a.estimate.totalBytes(), 4.0 * (1ull << 30)) << entry.path() << describeMemory(a.estimate);
  }
}

TEST(ResourceEstimate, BillionShadowPhotonsNeedMoreThanThisMachine) {
  const Scene scene = loadScene(kScenes + "fig14_cornell.json", {"photons.shadow=1000000000", "photons.gate=on"});
  const RenderPlan plan = makePlan(scene, Aov::Beauty);
  Admission a = admitJob(scene, plan, 2, false, 24ull << 30);
  TraceScene tracer(scene);
  EXPECT_THROW(confirmJob(a, scene, tracer, {}), InputError);
  EXPECT_GT(a.estimate.photonPeakBytes, double(24ull << 30));
}

TEST(ResourceEstimate, AHugeFrameSaysItsEstimateBeforeAnyPhotonOrTile) {
  // 16384^2 at 4096 spp: days, told through the notice before the first progress report.
  RenderRequest req;
  req.scenePath = kScenes + "fig03_shadows.json";
  req.overrides = {"camera.width=16384", "camera.height=16384", "camera.spp=4096"};
  std::string note;
  struct Phases final : ProgressPhases {
    bool begun = false;
    ProgressCounter* begin(const std::string&, uint64_t) override {
      begun = true;
      return nullptr;
    }
    void end() override {}
  } phases;
  struct Stop {};
  req.session.notice = [&](const std::string& n) { note = n; throw Stop{}; };
  req.session.progress = &phases;
  EXPECT_THROW(runRender(req), Stop);
  EXPECT_FALSE(phases.begun);
  EXPECT_NE(note.find("estimated ~"), std::string::npos) << note;
  EXPECT_NE(note.find(" h on "), std::string::npos) << note;
}

TEST(ResourceEstimate, SmallJobsSayNothing) {
  RenderRequest req;
  req.scenePath = kScenes + "fig03_shadows.json";
  req.overrides = {"camera.width=32", "camera.height=24", "photons.shadow=1000"};
  bool told = false;
  req.session.notice = [&](const std::string&) { told = true; };
  const RenderResult r = runRender(req);
  EXPECT_FALSE(told);
  EXPECT_LT(r.estimate.seconds(), kLongJobSeconds);
  EXPECT_GT(r.estimate.imageBytes, 32.0 * 24 * 12);
}

TEST(MemoryLimit, SizesParseInBinaryUnits) {
  EXPECT_EQ(parseMemorySize("8G"), 8ull << 30);
  EXPECT_EQ(parseMemorySize("512M"), 512ull << 20);
  EXPECT_EQ(parseMemorySize("1.5GiB"), 3ull << 29);
  EXPECT_EQ(parseMemorySize("64k"), 64ull << 10);
  EXPECT_EQ(parseMemorySize("2048"), 2048u);
  for (const char* bad : {"", "G", "0", "-1G", "8Q", "nan", "1e30G"}) {
    EXPECT_THROW(parseMemorySize(bad), InputError) << bad;
  }
  EXPECT_GT(availableMemoryBytes(), 0u);
}

// A sky is environment_sky's only light: every global photon starts at it, and each
// start is charged its map-less cost beyond the segment.
TEST(ResourceEstimate, EnvironmentPhotonsArePricedAtTheirStart) {
  const RenderResult r = render(kScenes + "environment_sky.json", {"camera.width=16", "camera.height=12"});
  const PhotonPlan& p = r.estimate.plan;
  ASSERT_GT(p.emitted[MapKind::Global], 0u);
  EXPECT_EQ(p.environmentPhotons, p.emitted[MapKind::Global] + p.emitted[MapKind::Caustic]);
  EXPECT_GE(r.estimate.photonSeconds * r.estimate.threads * 1e9,
            double(p.photonPasses) * double(p.environmentPhotons) * (cost::kPhotonSegmentNs + cost::kEnvironmentPhotonNs));
}

// A camera pilot's texture lookups are priced at kTextureLookupNs each, on every
// sample of every pass; without a pilot none are.
TEST(ResourceEstimate, TexturesAPilotCountsArePricedPerLookup) {
  const Scene scene = loadScene(kScenes + "fig15_globe.json");
  EstimateOptions o;
  o.photons.passes = 3;
  o.pointsPerSample = o.diffusePerSample = 0.5;
  o.missesPerSample = 0.5;
  const ResourceEstimate bare = estimateResources(scene, o, analyticStoreRates(scene));
  o.texturesPerSample = 0.5;
  const ResourceEstimate textured = estimateResources(scene, o, analyticStoreRates(scene));
  const double lookups = double(scene.camera.width) * scene.camera.height * scene.camera.spp * 3 * 0.5;
  EXPECT_NEAR(textured.renderSeconds - bare.renderSeconds, lookups * cost::kTextureLookupNs * 1e-9, 1e-9);
}

// An exact gather costs its base where the map fits the caches, and kGatherSlowdown
// more for each doubling of the map past them: fig14's indirect map, as its photon
// budget grows a hundredfold, costs more per shading point.
TEST(ResourceEstimate, AnExactGatherSlowsAsItsMapOutgrowsTheCaches) {
  using namespace cost;
  EXPECT_DOUBLE_EQ(gatherNsPerNeighbour(20.0, kGatherCacheBytes / 2), 20.0);
  EXPECT_DOUBLE_EQ(gatherNsPerNeighbour(20.0, kGatherCacheBytes * 8), 20.0 * (1.0 + 3.0 * kGatherSlowdown));
  Scene scene = loadScene(kScenes + "fig14_cornell.json");
  scene.camera.width = 64, scene.camera.height = 48;
  EstimateOptions o;
  o.photons.emitted[MapKind::Indirect] = 20000;
  const double small = estimateResources(scene, o, analyticStoreRates(scene)).renderSeconds;
  o.photons.emitted[MapKind::Indirect] = 2000000;
  const double large = estimateResources(scene, o, analyticStoreRates(scene)).renderSeconds;
  EXPECT_GT(large, small);
}
