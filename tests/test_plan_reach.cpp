// The reach pilot and the budget split it drives: first-hit fractions against solid
// angles, a light boxed in black getting no photons while the stored power stays that
// of the power split, the plan's reasons, and a global map no bounce can feed.
#include "plan/render_plan.h"
#include "support/emit_fixtures.h"
#include "plan/photon_stage.h"
#include "emit/emit.h"
#include "emit/light_reach.h"
#include "io/shapes.h"
#include "support/scene_fixtures.h"
#include <gtest/gtest.h>
#include <cmath>

namespace penumbra {
namespace {

// Light 0 halfway between a bouncing floor and ceiling (200 x 200, y = 0 and 2), and
// light 1 of the same power shut in a black box (p_r = p_t = 0) above the ceiling.
Scene boxedLightScene(uint64_t indirect) {
  Scene scene;
  Material floor = makeMaterial("floor", Color(0.0f), Color(0.8f));
  floor.pR = 0.5f;
  Material black = makeMaterial("black", Color(0.0f), Color(0.0f));
  scene.materials = {floor, black};
  scene.meshes.push_back(makeQuad(Vec3(-100, 0, 100), Vec3(200, 0, 0), Vec3(0, 0, -200), 0));
  scene.meshes.push_back(makeQuad(Vec3(-100, 2, -100), Vec3(200, 0, 0), Vec3(0, 0, 200), 0));
  scene.meshes.push_back(makeBox(Vec3(49, 4, 49), Vec3(51, 6, 51), 1));
  scene.lights = {point(Vec3(0, 1, 0), Color(1.0f), 1.0f), point(Vec3(50, 5, 50), Color(1.0f), 1.0f)};
  scene.photons.estimator = IndirectEstimator::Density;
  scene.photons.indirectPhotons = indirect;
  scene.photons.shadowPhotons = 0;
  scene.render.seed = 777;
  return scene;
}

// The share of a point light's directions that meet a centred square of half side a
// at distance h: solid angle 4 asin(a^2 / (a^2 + h^2)) over 4 pi.
double squareFraction(double a, double h) { return 4.0 * std::asin(a * a / (a * a + h * h)) / (4.0 * kPi); }

TEST(Reach, FirstHitFractionsMatchTheSolidAngles) {
  const Scene scene = boxedLightScene(0);
  const TraceScene tracer(scene);
  const double p = 2.0 * squareFraction(100.0, 1.0);  // 0.991: the slab's open rim lets 0.9% out
  const double sigma = std::sqrt(p * (1.0 - p) / kReachPilots);
  const std::vector<float> bouncing = measureReach(scene, tracer, ReachRule::Bouncing);
  ASSERT_EQ(bouncing.size(), 2u);
  EXPECT_NEAR(bouncing[0], p, 4.0 * sigma);  // light 0 meets only the floor and ceiling, which bounce
  EXPECT_EQ(bouncing[1], 0.0f);    // light 1 meets only black walls
}

TEST(Reach, MaterialRulesFollowWhatEachMapStores) {
  Scene scene;
  Material glass = makeMaterial("glass", Color(0.0f), Color(0.0f));
  glass.transparent = true;
  Material black = makeMaterial("black", Color(0.0f), Color(0.0f));
  Material grey = makeMaterial("grey", Color(0.0f), Color(0.5f));
  scene.materials = {glass, black, grey};
  EXPECT_TRUE(reaches(scene, 0, ReachRule::Specular));
  EXPECT_FALSE(reaches(scene, 2, ReachRule::Specular));
  EXPECT_FALSE(reaches(scene, 1, ReachRule::Scattering));
  EXPECT_TRUE(reaches(scene, 2, ReachRule::Scattering));
  EXPECT_FALSE(reaches(scene, 2, ReachRule::Bouncing));  // p_r = p_t = 0
}

double storedPower(const EmittedPhotons& maps) {
  double sum = 0.0;
  for (const IndirectPhoton& ph : maps.batches.get<MapKind::Indirect>()) sum += luminance(ph.power.color());
  return sum;
}

TEST(Reach, ABoxedLightGetsNoPhotonsAndTheStoredPowerIsUnchanged) {
  const Scene scene = boxedLightScene(200000);
  const TraceScene tracer(scene);
  EmitOptions bySplit;
  bySplit.maps[MapKind::Shadow] = false;
  EmitOptions byReach = bySplit;
  byReach.reach[MapKind::Indirect] = measureReach(scene, tracer, ReachRule::Bouncing);
  EXPECT_EQ(splitBudget(scene, 200000), (std::vector<uint64_t>{100000, 100000}));
  EXPECT_EQ(splitBudget(scene, 200000, byReach.reach[MapKind::Indirect]), (std::vector<uint64_t>{200000, 0}));
  const EmittedPhotons power = emitPhotons(scene, tracer, sceneEmit(scene, bySplit));
  const EmittedPhotons reach = emitPhotons(scene, tracer, sceneEmit(scene, byReach));
  // Every stored photon is light 0's (light 1's die in the black box, unstored: the
  // density estimator stores from the second hit): twice as many of them at half
  // the power each, so the same flux with less noise.
  const double countRatio = double(reach.batches.get<MapKind::Indirect>().size()) / double(power.batches.get<MapKind::Indirect>().size());
  EXPECT_NEAR(countRatio, 2.0, 0.05) << reach.batches.get<MapKind::Indirect>().size() << " vs " << power.batches.get<MapKind::Indirect>().size();
  // ~100k stored photons on the power split's side: the flux estimates agree within
  // a few percent (roulette and direction noise, ~0.5% each).
  EXPECT_NEAR(storedPower(reach) / storedPower(power), 1.0, 0.03);
  RecordProperty("count_ratio", std::to_string(countRatio));
  RecordProperty("power_ratio", std::to_string(storedPower(reach) / storedPower(power)));
}

// The classic estimator averages photon colours: a split away from power would
// change its expectation, so its indirect pass keeps the power split.
TEST(Reach, TheClassicEstimatorKeepsThePowerSplit) {
  Scene scene = boxedLightScene(100000);
  scene.photons.estimator = IndirectEstimator::Classic;
  const TraceScene tracer(scene);
  RenderPlan plan = makePlan(scene, Aov::Beauty);
  splitByReach(plan, scene, tracer);
  EXPECT_TRUE(plan[Pass::IndirectPhotons].reach.empty());
  EXPECT_EQ(plan[Pass::IndirectPhotons].perLight, (std::vector<uint64_t>{50000, 50000}));
}

TEST(Reach, ThePlanSaysWhichLightsGetNothingAndTurnsOffAPassNoLightFeeds) {
  Scene scene = boxedLightScene(100000);
  const TraceScene tracer(scene);
  RenderPlan plan = makePlan(scene, Aov::Beauty);
  ASSERT_TRUE(plan[Pass::IndirectPhotons].on);
  splitByReach(plan, scene, tracer);
  const PassDecision& d = plan[Pass::IndirectPhotons];
  EXPECT_TRUE(d.on);
  EXPECT_EQ(d.perLight, (std::vector<uint64_t>{100000, 0}));
  EXPECT_NE(d.reason.find("1 of 2 lights reach none"), std::string::npos) << d.reason;

  // Only the boxed light: nothing it emits can be stored, so the pass goes off.
  scene.lights.erase(scene.lights.begin());
  const TraceScene boxedOnly(scene);
  RenderPlan alone = makePlan(scene, Aov::Beauty);
  splitByReach(alone, scene, boxedOnly);
  EXPECT_FALSE(alone[Pass::IndirectPhotons].on);
  EXPECT_NE(alone[Pass::IndirectPhotons].reason.find("no light's photons reach"), std::string::npos);
  EXPECT_EQ(planBudgets(alone)[MapKind::Indirect], 0u);

  // Forced on, the pass keeps the power split: "everything" means everything.
  PlanOverrides force;
  force.enable = {Pass::IndirectPhotons};
  scene.photons.indirectPhotons = 100000;
  RenderPlan forced = makePlan(scene, Aov::Beauty, force);
  splitByReach(forced, scene, boxedOnly);
  EXPECT_TRUE(forced[Pass::IndirectPhotons].reach.empty());
}

// The physical global map stores from the second hit on: a lone convex box under a
// light leaves every bounce free, so no pilot lands and the pass goes off; a floor
// under the same box catches bounces, and the pass stays on.
TEST(Reach, AGlobalMapNoBounceCanFeedIsTurnedOff) {
  Scene scene;
  scene.render.model = ShadingModel::Physical;
  scene.materials = {makeMaterial("grey", Color(0.0f), Color(0.5f))};
  scene.meshes.push_back(makeBox(Vec3(-1, 0, -1), Vec3(1, 2, 1), 0));
  scene.lights = {point(Vec3(3, 4, 2), Color(1.0f), 1.0f)};
  scene.photons.globalPhotons = 100000;
  const TraceScene lone(scene);
  EXPECT_EQ(measureRebound(scene, lone), 0.0f);
  RenderPlan plan = makePlan(scene, Aov::Beauty);
  ASSERT_TRUE(plan[Pass::GlobalPhotons].on);
  splitByReach(plan, scene, lone);
  EXPECT_FALSE(plan[Pass::GlobalPhotons].on);
  EXPECT_NE(plan[Pass::GlobalPhotons].reason.find("land on a second surface"), std::string::npos)
      << plan[Pass::GlobalPhotons].reason;
  EXPECT_EQ(planBudgets(plan)[MapKind::Global], 0u);

  scene.meshes.push_back(makeQuad(Vec3(-50, 0, 50), Vec3(100, 0, 0), Vec3(0, 0, -100), 0));
  const TraceScene floored(scene);
  EXPECT_GT(measureRebound(scene, floored), 0.0f);  // the floor sends some bounces into the box
  RenderPlan kept = makePlan(scene, Aov::Beauty);
  splitByReach(kept, scene, floored);
  EXPECT_TRUE(kept[Pass::GlobalPhotons].on);
  EXPECT_EQ(planBudgets(kept)[MapKind::Global], 100000u);
}

}  // namespace
}  // namespace penumbra
