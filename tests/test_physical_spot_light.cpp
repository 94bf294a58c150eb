// Spot lights against closed forms: glTF's falloff (the square of a linear ramp
// between the cones) on a plane in both models, photons that stay inside the
// outer cone and carry the spot's power on average, and the JSON keys (glTF's:
// test_io_model_import).
#include "core/error.h"
#include "core/light_sample.h"
#include "io/scene_loader.h"
#include "support/physical_fixtures.h"

namespace penumbra {
namespace {

constexpr double kDeg = kPiD / 180.0;

// A spot 2 above the plane y = 0, shining straight down, cones 20 and 40 degrees.
Light downSpot() {
  Light l = point(Vec3(0.0f, 2.0f, 0.0f), Color(1.0f, 0.8f, 0.6f), 5.0f);
  l.direction = Vec3(0.0f, -1.0f, 0.0f);
  setSpotCone(l, float(20.0 * kDeg), float(40.0 * kDeg));
  return l;
}

// glTF's falloff written out: t = (cos - cos_o) / (cos_i - cos_o), clamped, squared.
double falloff(double angleDeg) {
  const double c = std::cos(angleDeg * kDeg), ci = std::cos(20.0 * kDeg), co = std::cos(40.0 * kDeg);
  const double t = std::clamp((c - co) / (ci - co), 0.0, 1.0);
  return t * t;
}

TEST(SpotLight, APlaneUnderASpotIsThePointLightTimesTheFalloffInBothModels) {
  // Points of the plane seen at 10, 25, 35 and 50 degrees off the spot's axis: the
  // point light's closed form times the falloff (1, a ramp, 0). Physical rho/pi I cos
  // / d^2; classic k_d I cos / d^2 (no 1/pi, no ambient). Tolerance 1e-4 relative,
  // 1e-7 absolute where the answer is 0.
  for (ShadingModel model : {ShadingModel::Physical, ShadingModel::Classic}) {
    Scene scene = physicalScene();
    scene.render.model = model;
    scene.materials.push_back(lambert("plane", Color(0.5f)));
    scene.meshes.push_back(makeQuad(Vec3(-50, 0, -50), Vec3(0, 0, 100), Vec3(100, 0, 0), 0));
    scene.lights.push_back(downSpot());
    Rig rig(scene);
    const Vec3 eye(0.3f, 4.0f, 3.0f);
    for (double angle : {10.0, 25.0, 35.0, 50.0}) {
      const Vec3 p(float(2.0 * std::tan(angle * kDeg)), 0.0f, 0.0f);
      const Ray ray = makeRay(eye, p - eye);
      const Color got = model == ShadingModel::Physical ? trace(rig, ray, kTermAll) : rig.shade(ray);
      const double d2 = 4.0 + double(p.x) * p.x, cosT = 2.0 / std::sqrt(d2);
      for (int c = 0; c < 3; ++c) {
        const double rho = model == ShadingModel::Physical ? 0.5 / kPiD : 0.5;
        const double want = rho * scene.lights[0].radiance()[c] * cosT / d2 * falloff(angle);
        if (want == 0.0) EXPECT_NEAR(got[c], 0.0, 1e-7) << angle;
        else EXPECT_LT(rel(got[c], want), 1e-4) << int(model) << " at " << angle << " deg: " << got[c] << " vs " << want;
      }
    }
  }
}

TEST(SpotLight, PhotonsLeaveInsideTheOuterConeAndCarryItsPowerOnAverage) {
  // Power = I x the falloff's integral over the sphere (checked against a midpoint
  // quadrature in angle, 1e-4 relative); photon directions never leave the outer cone
  // and their weights average 1 (stratified samples, 1e-3).
  const Light spot = downSpot();
  double integral = 0.0;
  const int steps = 20000;
  for (int i = 0; i < steps; ++i) {
    const double theta = (i + 0.5) * kPiD / steps;
    integral += falloff(theta / kDeg) * 2.0 * kPiD * std::sin(theta) * (kPiD / steps);
  }
  EXPECT_LT(rel(spotSolidAngle(spot), integral), 1e-4);
  EXPECT_LT(rel(lightPower(spot, SceneSphere{}).g, spot.radiance().g * integral), 1e-4);
  const int n = 256;
  double sum = 0.0;
  for (int i = 0; i < n; ++i) {
    for (int j = 0; j < n; ++j) {
      const PhotonRay r = sampleLightPhoton(spot, SceneSphere{}, (i + 0.5f) / n, (j + 0.5f) / n, 0.5f, 0.5f);
      EXPECT_GE(glm::dot(r.dir, spot.direction), spot.spotCosOuter - 1e-6f);
      sum += r.weight.g;
    }
  }
  EXPECT_NEAR(sum / (double(n) * n), 1.0, 1e-3);
}

TEST(SpotLight, JsonKeysMakeTheConeAndAnInvertedOneIsRefused) {
  const Scene s = parseScene(R"({"lights": [{"type": "spot", "position": [0, 3, 0], "direction": [0, -2, 0],
      "inner_angle": 15, "outer_angle": 30, "intensity": 4}]})",
                             "x.json");
  ASSERT_EQ(s.lights.size(), 1u);
  EXPECT_TRUE(s.lights[0].isSpot());
  EXPECT_NEAR(s.lights[0].spotCosInner, std::cos(15.0 * kDeg), 1e-6);
  EXPECT_NEAR(s.lights[0].spotCosOuter, std::cos(30.0 * kDeg), 1e-6);
  EXPECT_EQ(s.lights[0].direction, Vec3(0, -1, 0));
  try {
    parseScene(R"({"lights": [{"type": "spot", "position": [0, 3, 0], "direction": [0, -1, 0],
        "inner_angle": 30, "outer_angle": 30}]})",
               "x.json");
    FAIL() << "inner >= outer must be refused";
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find("lights[0].inner_angle"), std::string::npos) << e.what();
  }
}

}  // namespace
}  // namespace penumbra
