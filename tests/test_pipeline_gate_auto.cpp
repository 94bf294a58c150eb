// photons.gate = auto: the cost model turns the gate off where a point light saves
// one cheap ray per shading point, and on for 16-sample area lights; the decision
// and its reason reach the stats, and an explicit on/off always wins.
#include "cli/gate_decision.h"
#include "cli/pipeline.h"
#include "io/scene_loader.h"
#include <gtest/gtest.h>

using namespace penumbra;

namespace {

const std::string kScenes = std::string(PENUMBRA_SOURCE_DIR) + "/scenes/";

TEST(GateAuto, PointLightSceneDecidesOffAndSaysWhy) {
  const Scene scene = loadScene(kScenes + "fig03_shadows.json", {});
  EXPECT_EQ(scene.photons.gateMode, GateMode::Auto);  // the default
  const GateDecision d = decideGate(scene);
  EXPECT_FALSE(d.gate);
  EXPECT_LT(d.savedMs, d.costMs);
  EXPECT_NE(d.reason.find("auto: off"), std::string::npos) << d.reason;
}

TEST(GateAuto, SoftShadowSceneDecidesOn) {
  const Scene scene = loadScene(kScenes + "soft_shadows.json", {});
  const GateDecision d = decideGate(scene);
  EXPECT_TRUE(d.gate) << d.reason;
  // 2 area lights x 16 samples: the saving grows with the samples, the cost does not.
  const GateDecision four = decideGate(loadScene(kScenes + "soft_shadows.json", {"render.light_samples=4"}));
  EXPECT_LT(four.savedMs, d.savedMs / 3.9);
  EXPECT_DOUBLE_EQ(four.costMs, d.costMs);
  EXPECT_FALSE(decideGate(loadScene(kScenes + "soft_shadows.json", {"render.shadows=false"})).gate);
}

TEST(GateAuto, RenderSkipsTheShadowMapUnlessAskedFor) {
  RenderRequest req;
  req.scenePath = kScenes + "fig03_shadows.json";
  req.overrides = {"camera.width=64", "camera.height=48", "photons.shadow=50000"};
  RenderResult autoRun = runRender(req);
  EXPECT_FALSE(autoRun.stats.gate);
  EXPECT_EQ(autoRun.stats.gateMode, "auto");
  EXPECT_EQ(autoRun.stats.storedShadow, 0u);  // no shadow photons emitted at all
  EXPECT_EQ(autoRun.stats.rays.gateQueries, 0u);
  EXPECT_FALSE(autoRun.stats.gateReason.empty());
  req.overrides.push_back("photons.gate=on");
  RenderResult on = runRender(req);
  EXPECT_TRUE(on.stats.gate);
  EXPECT_GT(on.stats.storedShadow, 0u);
  EXPECT_GT(on.stats.rays.gateQueries, 0u);
  req.overrides.back() = "photons.gate=off";
  EXPECT_FALSE(runRender(req).stats.gate);
}

}  // namespace
