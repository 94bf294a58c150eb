// The plan's media decisions on hand-built scenes: the volume pass only where a medium
// scatters light, its reason naming the media, the physical model's volume gather per
// pass, the estimates and reuse keys that cover the volume map, and nothing of media
// anywhere in a scene without one.
#include "io/scene_loader.h"
#include "io/shapes.h"
#include "plan/render_plan.h"
#include "plan/resource_estimate.h"
#include "plan/reuse_key.h"
#include "plan/sweep/sweep_spec.h"
#include "plan/transport_model.h"
#include "gather/radiance_estimate.h"
#include "support/scene_fixtures.h"
#include <gtest/gtest.h>
#include <nlohmann/json.hpp>
#include <cmath>
#include <filesystem>
#include <functional>

namespace penumbra {
namespace {

Medium medium(const std::string& name, float sigmaS, float sigmaA = 0.01f) {
  Medium m;
  m.name = name;
  m.sigmaS = Color(sigmaS);
  m.sigmaA = Color(sigmaA);
  return m;
}

// A diffuse floor under a point light, seen from above; fog fills it unless `fog` is false.
Scene floorScene(bool fog = true) {
  Scene scene;
  scene.render.model = ShadingModel::Physical;
  scene.materials = {makeMaterial("floor", Color(0.0f), Color(0.5f))};
  scene.meshes.push_back(makeQuad(Vec3(-5, 0, 5), Vec3(10, 0, 0), Vec3(0, 0, -10), 0));
  scene.lights = {point(Vec3(0, 4, 0), Color(1.0f), 10.0f)};
  scene.camera = axisCamera(Vec3(0, 3, 8), Vec3(0, 0, 0));
  scene.camera.width = 64;
  scene.camera.height = 48;
  if (fog) {
    scene.media = {medium("fog", 0.1f)};
    scene.sceneMedium = scene.cameraMedium = 0;
  }
  return scene;
}

TEST(MediaPlan, VolumePhotonsRunOnlyWhereAMediumScattersLight) {
  const Scene fog = floorScene();
  const RenderPlan plan = makePlan(fog, Aov::Beauty);
  EXPECT_TRUE(plan[Pass::VolumePhotons].on);
  EXPECT_EQ(plan[Pass::VolumePhotons].reason, "medium 'fog' scatters: 200000 photons per pass");
  EXPECT_EQ(plan[Pass::VolumePhotons].budget, 200000u);
  EXPECT_NE(planText(plan).find("volume-photons    on   medium 'fog' scatters: 200000 photons per pass"),
            std::string::npos)
      << planText(plan);

  struct Case {
    const char* what;
    std::function<void(Scene&)> change;
    Aov aov;
    const char* reason;
  };
  const std::vector<Case> cases = {
      {"no medium", [](Scene& s) { s = floorScene(false); }, Aov::Beauty, "no medium"},
      {"sigma_s 0", [](Scene& s) { s.media[0].sigmaS = Color(0.0f); }, Aov::Beauty,
       "no medium scatters (every sigma_s is 0)"},
      {"no light", [](Scene& s) { s.lights.clear(); }, Aov::Beauty, "no light"},
      {"no photons", [](Scene& s) { s.photons.volumePhotons = 0; }, Aov::Beauty, "photons.volume is 0"},
      {"no bounces", [](Scene& s) { s.photons.maxBounces = 0; }, Aov::Beauty, "photons.max_bounces is 0"},
      {"classic", [](Scene& s) { s.render.model = ShadingModel::Classic; }, Aov::Beauty,
       "the classic model has no volume map"},
      {"depth view", [](Scene&) {}, Aov::Depth, "the depth view reads no light"},
      {"caustic view", [](Scene&) {}, Aov::Caustic, "this view does not read it (single scattering is direct light)"},
      {"direct view", [](Scene&) {}, Aov::Direct, "this view does not read it (single scattering is direct light)"},
  };
  for (const Case& c : cases) {
    Scene s = floorScene();
    c.change(s);
    const RenderPlan decided = makePlan(s, c.aov);
    const PassDecision& d = decided[Pass::VolumePhotons];
    EXPECT_FALSE(d.on) << c.what;
    EXPECT_EQ(d.reason, c.reason) << c.what;
  }
  EXPECT_TRUE(makePlan(fog, Aov::Indirect)[Pass::VolumePhotons].on);

  // Several media: those that scatter are named; an absorbing one is not.
  Scene three = floorScene();
  three.media = {medium("fog", 0.1f), medium("ink", 0.0f, 1.0f), medium("smoke", 0.5f)};
  EXPECT_EQ(makePlan(three, Aov::Beauty)[Pass::VolumePhotons].reason,
            "media 'fog' and 'smoke' scatter: 200000 photons per pass");
}

TEST(MediaPlan, ForcedOnWithoutAMediumItCarriesTheBudget) {
  Scene plain = floorScene(false);
  plain.photons.volumePhotons = 1234;
  const RenderPlan forced = makePlan(plain, Aov::Beauty, {{Pass::VolumePhotons}, {}});
  EXPECT_TRUE(forced[Pass::VolumePhotons].on);
  EXPECT_EQ(forced[Pass::VolumePhotons].budget, 1234u);
  EXPECT_FALSE(forced[Pass::VolumePhotons].changesImage);  // nothing to scatter in: nothing stored
}

// Pass i gathers passK(k_volume) photons, or a fixed radius shrunk by sqrt(passRadiusShare).
TEST(MediaPlan, TheVolumeGatherShrinksLikeTheSurfaceMaps) {
  PhotonSettings ps;
  ps.kVolume = 120;
  for (uint32_t pass : {0u, 1u, 5u}) {
    const PhotonGather g = physicalTransport().gathers(ps, pass, 8)[MapKind::Volume];
    EXPECT_EQ(g.k, passK(120, pass, ps.alpha)) << pass;
    EXPECT_EQ(g.maxRadius, 0.0f) << pass;
  }
  EXPECT_EQ(physicalTransport().gathers(ps, 0, 1)[MapKind::Volume].k, 120);
  ps.volumeRadius = 0.2f;
  ps.radius = 0.5f;  // the surface maps' fixed radius leaves the volume map's alone
  const PhotonGather g = physicalTransport().gathers(ps, 3, 8)[MapKind::Volume];
  EXPECT_NEAR(g.maxRadius, 0.2 * std::sqrt(passRadiusShare(3, ps.alpha)), 1e-6);
  EXPECT_EQ(g.k, passK(120, 3, ps.alpha));
  EXPECT_TRUE(physicalTransport().readsMap(MapKind::Volume, Aov::Beauty));
  EXPECT_TRUE(physicalTransport().readsMap(MapKind::Volume, Aov::Indirect));
  EXPECT_FALSE(physicalTransport().readsMap(MapKind::Volume, Aov::Caustic));
}

// The image's settings line and keys say nothing of media in a scene without one.
TEST(MediaPlan, SettingsNameTheVolumeMapOnlyWithAMedium) {
  MapCounts budgets;
  budgets[MapKind::Volume] = 5000;
  RenderStats stats;
  const std::string plain = physicalTransport().photonSummary(floorScene(false), budgets, stats, false);
  EXPECT_EQ(plain.find("volume"), std::string::npos) << plain;
  const std::string fog = physicalTransport().photonSummary(floorScene(), budgets, stats, false);
  EXPECT_NE(fog.find("volume_photons=5000 k_volume=100 volume_radius=0"), std::string::npos) << fog;
  ImageMetadata none, some;
  physicalTransport().addModelSettings(floorScene(false), budgets, stats, none);
  physicalTransport().addModelSettings(floorScene(), budgets, stats, some);
  for (const auto& [key, value] : none) EXPECT_EQ(key.find("volume"), std::string::npos) << key;
  EXPECT_EQ(some.size(), none.size() + 3);
}

EstimateOptions optionsFor(const Scene& scene) {
  const RenderPlan plan = makePlan(scene, Aov::Beauty);
  EstimateOptions o;
  for (MapKind k : kAllMaps) o.photons.emitted[k] = plan[photonPass(k)].on ? plan[photonPass(k)].budget : 0;
  return o;
}

// The estimate prices volume photons and the camera rays' medium work, and only
// where rays meet a medium: a small box far off costs a small share of the rays.
TEST(MediaPlan, TheEstimatePricesMediaOnlyWhereRaysMeetThem) {
  const Scene plain = floorScene(false);
  const ResourceEstimate none = estimateResources(plain, optionsFor(plain), analyticStoreRates(plain));
  EXPECT_FALSE(none.media.any);
  EXPECT_FALSE(nlohmann::json::parse(estimateToJson(none)).contains("media"));
  EXPECT_EQ(none.rates.perPhoton[MapKind::Volume], 0.0);

  const Scene fog = floorScene();
  const ResourceEstimate filled = estimateResources(fog, optionsFor(fog), analyticStoreRates(fog));
  ASSERT_TRUE(filled.media.any);
  EXPECT_EQ(filled.media.cameraShare, 1.0);
  EXPECT_GT(filled.media.gatherNs, 0.0);
  EXPECT_GT(filled.mediaCameraSeconds, 0.0);
  EXPECT_GT(filled.mediaPhotonSeconds, 0.0);
  EXPECT_GT(filled.rates.perPhoton[MapKind::Volume], 0.0);
  EXPECT_LE(filled.rates.perPhoton[MapKind::Volume], fog.photons.maxBounces);
  EXPECT_GT(filled.renderSeconds, none.renderSeconds);
  EXPECT_GT(filled.photonSeconds, none.photonSeconds);
  EXPECT_TRUE(nlohmann::json::parse(estimateToJson(filled)).contains("media"));

  // A box of fog 0.2 across, 8 units from the camera: under 1% of the view.
  Scene box = floorScene(false);
  box.media = {medium("fog", 0.1f)};
  box.boundaryMeshes.push_back(makeBox(Vec3(-0.1f, 0.5f, -0.1f), Vec3(0.1f, 0.7f, 0.1f)));
  box.boundaryMeshes.back().media = {0, kNoMedium, true};
  const ResourceEstimate small = estimateResources(box, optionsFor(box), analyticStoreRates(box));
  EXPECT_GT(small.media.cameraShare, 0.0);
  EXPECT_LT(small.media.cameraShare, 0.01);
  EXPECT_LT(small.mediaCameraSeconds, 0.01 * filled.mediaCameraSeconds);
}

// --photons and --k vary the volume map in a scene with a medium, and only there.
TEST(MediaPlan, SweepKnobsReachTheVolumeMapWithAMedium) {
  const SweepKnob plain = namedKnob("photons", "1e4,1e5", physicalTransport());
  EXPECT_EQ(plain.keys, (std::vector<std::string>{"photons.global", "photons.caustic"}));
  const SweepKnob photons = namedKnob("photons", "1e4,1e5", physicalTransport(), true);
  EXPECT_EQ(photons.keys, (std::vector<std::string>{"photons.global", "photons.caustic", "photons.volume"}));
  const SweepKnob k = namedKnob("k", "10,50", physicalTransport(), true);
  EXPECT_EQ(k.keys, (std::vector<std::string>{"photons.k_global", "photons.k_caustic", "photons.k_volume"}));
}

// The volume map's budget, k and radius share one emission (a smaller budget is a
// prefix); the medium filling the scene and the media themselves are geometry.
TEST(MediaPlan, ReuseKeysCoverTheMedia) {
  const std::string fog = std::string(PENUMBRA_SOURCE_DIR) + "/scenes/cornell_fog.json";
  const ReuseKeys keys = reuseKeys(fog, {});
  for (const char* same : {"photons.volume=1000", "photons.k_volume=7", "photons.volume_radius=0.1"}) {
    const ReuseKeys k = reuseKeys(fog, {same});
    EXPECT_EQ(k.photons, keys.photons) << same;
    EXPECT_EQ(k.geometry, keys.geometry) << same;
  }
  for (const char* geometry : {"render.medium=\"none\"", "media[0].sigma_s=0.3", "media[0].g=0.5"}) {
    const ReuseKeys k = reuseKeys(fog, {geometry});
    EXPECT_NE(k.photons, keys.photons) << geometry;
    EXPECT_NE(k.geometry, keys.geometry) << geometry;
  }
}

// A density grid's .vdb is one of the scene's inputs: editing it changes the stamp
// both reuse keys carry, so batch and sweep never share a stale grid's photons.
TEST(MediaPlan, AGridFileIsAnInputOfBothKeys) {
  namespace fs = std::filesystem;
  const fs::path dir = fs::temp_directory_path() / "penumbra_test_plan_media_grid";
  fs::create_directories(dir);
  for (const char* f : {"smoke.json", "smoke.vdb"}) {
    fs::copy_file(fs::path(PENUMBRA_SOURCE_DIR) / "scenes" / f, dir / f, fs::copy_options::overwrite_existing);
  }
  const Scene scene = loadScene((dir / "smoke.json").string());
  const auto vdb = std::find_if(scene.inputs.begin(), scene.inputs.end(),
                                [](const std::string& p) { return fs::path(p).extension() == ".vdb"; });
  ASSERT_NE(vdb, scene.inputs.end());
  const std::string before = inputsStamp(scene.inputs);
  fs::last_write_time(*vdb, fs::last_write_time(*vdb) + std::chrono::seconds(5));
  EXPECT_NE(inputsStamp(scene.inputs), before);
  fs::remove_all(dir);
}

}  // namespace
}  // namespace penumbra
