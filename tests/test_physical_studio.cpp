// The physical model under the studio environment against its closed forms: a Lambert
// sphere of albedo rho (1: the white furnace, 0.5: rho L) shows rho E(n) / pi at points
// of known normal, its MIS estimate (the map drawn by luminance, the BSDF by cosine)
// within 0.5%; camera rays that miss see the grey background, other rays the studio.
#include "core/lights/studio_environment.h"
#include "support/physical_fixtures.h"
#include "support/studio_closed_form.h"
#include "trace/environment_light.h"

namespace penumbra {
namespace {

Scene sphereInStudio(float rho) {
  Scene scene = physicalScene();
  scene.render.lightSamples = 64;
  scene.materials.push_back(lambert("ball", Color(rho)));
  scene.spheres.push_back({Vec3(0.0f), 1.0f, 0});
  addStudioEnvironment(scene, Color(1.0f), 1.0f, 0.0f);
  return scene;
}

class StudioSphere : public ::testing::TestWithParam<float> {};

TEST_P(StudioSphere, LambertSphereShowsRhoTimesTheClosedFormIrradianceOverPi) {
  // A unit sphere alone: nothing shadows a point's hemisphere, no photons, so the
  // pixel is the direct term, rho/pi E(n). Each normal is seen head-on from 3 n and
  // averaged over 1024 samples of 64 light + 64 BSDF samples; the standard error (from
  // the spread of the samples, printed) is below 0.1%, the tolerance 0.5% relative.
  const float rho = GetParam();
  const Scene scene = sphereInStudio(rho);
  Rig rig(scene);
  const int runs = 1024;
  for (const glm::dvec3& n : testing::studioTestNormals()) {
    const Vec3 nf(n);
    const auto [mean, se] = meanOverSamples(rig, makeRay(3.0f * nf, -nf), runs, 11, kTermAll);
    const double want = rho / kPiD * testing::studioIrradiance(n);
    std::printf("rho %.2f, n (%.3f, %.3f, %.3f): %.5f, want %.5f (standard error %.3f%%)\n", rho, n.x, n.y, n.z,
                mean, want, 100.0 * se / want);
    EXPECT_LT(rel(mean, want), 5e-3) << n.x << " " << n.y << " " << n.z;
  }
}

// Named rho_1_00 (the white furnace) and rho_0_50.
INSTANTIATE_TEST_SUITE_P(Albedo, StudioSphere, ::testing::Values(1.0f, 0.5f),
                         [](const ::testing::TestParamInfo<float>& tp) {
                           const int c = int(std::lround(tp.param * 100.0f));
                           return "rho_" + std::to_string(c / 100) + "_" + (c % 100 < 10 ? "0" : "") +
                                  std::to_string(c % 100);
                         });

TEST(StudioSphere, CameraRaysThatMissSeeTheGreyOthersTheStudio) {
  // The background is a camera ray's alone: a reflection ray along the same direction
  // sees the map's texel (the key, bright, straight along its axis). In the physical
  // model the grey is the background term, not the environment's glow.
  const Scene scene = sphereInStudio(0.5f);
  Rig rig(scene);
  const Vec3 key(studioKeyDirection());
  const Ray ray = makeRay(Vec3(0.0f, 0.0f, 5.0f) + 3.0f * key, key);
  expectColorNear(trace(rig, ray, kTermAll), Color(studio::kBackground), 0.0f, "camera ray");
  expectColorNear(trace(rig, ray, kTermMissed), Color(studio::kBackground), 0.0f, "background term");
  expectColorNear(trace(rig, ray, kTermEmitters), Color(0.0f), 0.0f, "no glow");
  const Color seen = missRadiance(scene, key, RayKind::Reflection);
  EXPECT_GT(seen.r, 0.9 * studio::kKey);
  EXPECT_EQ(missRadiance(scene, key, RayKind::Camera), Color(studio::kBackground));
  // Classic sees the same background.
  Scene classic = scene;
  classic.render.model = ShadingModel::Classic;
  Rig classicRig(classic);
  expectColorNear(classicRig.shade(ray), Color(studio::kBackground), 0.0f, "classic camera ray");
}

}  // namespace
}  // namespace penumbra
