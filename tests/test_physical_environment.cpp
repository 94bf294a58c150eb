// The environment light through both integrators against closed forms: a Lambert
// sphere alone in a constant sky (physical rho L, classic k_d pi L at every point),
// rays that leave the scene seeing the sky, and a plane under a lat-long map whose
// MIS estimate (light and BSDF samples) converges to rho / pi x the map's irradiance.
#include "core/lights/environment_map.h"
#include "support/physical_fixtures.h"

namespace penumbra {
namespace {

const Color kSky(0.8f, 1.0f, 1.2f);
constexpr float kSkyIntensity = 2.0f;

// A unit sphere at the origin, rho (or k_d) 0.5 and no ambient, under a constant sky;
// no photons, no gate: direct light by shadow rays only.
Scene sphereInSky(ShadingModel model, int lightSamples) {
  Scene scene = physicalScene();
  scene.render.model = model;
  scene.render.lightSamples = lightSamples;
  scene.materials.push_back(lambert("ball", Color(0.5f)));
  scene.spheres.push_back({Vec3(0.0f), 1.0f, 0});
  scene.lights.push_back(makeEnvironmentLight(kSky, kSkyIntensity, nullptr));
  return scene;
}

// Camera rays at points all over the sphere's visible side, from three eyes.
std::vector<Ray> raysOntoSphere() {
  std::vector<Ray> rays;
  for (const Vec3 eye : {Vec3(0.0f, 0.0f, 5.0f), Vec3(3.0f, 2.5f, -2.0f), Vec3(-1.0f, -4.0f, 0.5f)}) {
    Vec3 t, b;
    const Vec3 toEye = glm::normalize(eye);
    orthonormalBasis(toEye, t, b);
    for (float a : {-0.9f, -0.5f, 0.0f, 0.3f, 0.85f}) {
      for (float c : {-0.8f, -0.2f, 0.4f, 0.9f}) {
        if (a * a + c * c >= 0.98f) continue;
        const Vec3 p = glm::normalize(a * t + c * b + std::sqrt(1.0f - a * a - c * c) * toEye);
        rays.push_back(makeRay(eye, p - eye));
      }
    }
  }
  return rays;
}

TEST(EnvironmentLight, LambertSphereInAConstantSkyIsRhoL) {
  // Physical: L_o = rho/pi x the integral of L cos over the hemisphere = rho L, at
  // every point (a convex sphere shadows none of its own hemisphere). The sky is
  // sampled cosine-weighted about the normal and the BSDF samples are cosine too, so
  // every sample (both strategies, power heuristic weights 1/2 each) is rho L itself:
  // exact up to float rounding. Tolerance 0.5% relative, asked of every point; also with
  // a single light sample.
  for (int samples : {1, 16}) {
    const Scene scene = sphereInSky(ShadingModel::Physical, samples);
    Rig rig(scene);
    for (const Ray& ray : raysOntoSphere()) {
      const Color got = trace(rig, ray, kTermAll);
      for (int c = 0; c < 3; ++c) {
        const double want = 0.5 * kSky[c] * kSkyIntensity;
        EXPECT_LT(rel(got[c], want), 5e-3) << samples << " samples, ch " << c << ": " << got[c] << " vs " << want;
      }
    }
  }
}

TEST(EnvironmentLight, ClassicSphereInAConstantSkyIsKdPiL) {
  // Classic lights carry no 1/pi (a point light gives k_d I cos / d^2), so a sky gives
  // k_d E = k_d pi L, plus the ambient term (0 here). Cosine-weighted sky samples make
  // every sample exact; tolerance 0.5% relative at every point.
  const Scene scene = sphereInSky(ShadingModel::Classic, 4);
  Rig rig(scene);
  for (const Ray& ray : raysOntoSphere()) {
    const Color got = rig.shade(ray);
    for (int c = 0; c < 3; ++c) {
      const double want = 0.5 * kPiD * kSky[c] * kSkyIntensity;
      EXPECT_LT(rel(got[c], want), 5e-3) << "ch " << c << ": " << got[c] << " vs " << want;
    }
  }
}

TEST(EnvironmentLight, RaysThatLeaveTheSceneSeeTheSky) {
  // A camera ray that misses returns the environment's radiance, not render.background,
  // in both models; the map's texel along the ray (exact: no sampling).
  std::vector<Color> texels(8 * 4, Color(0.1f));
  texels[1 * 8 + 4] = Color(3.0f, 2.0f, 1.0f);  // row 1, column 4: theta in [45, 90), phi in [180, 225)
  for (ShadingModel model : {ShadingModel::Physical, ShadingModel::Classic}) {
    Scene scene = sphereInSky(model, 4);
    scene.render.background = Color(0.7f, 0.0f, 0.0f);
    scene.lights.back() = makeEnvironmentLight(Color(1.0f), 2.0f, makeEnvironmentMap(8, 4, texels, 0.0f));
    Rig rig(scene);
    // theta 60 degrees, phi 200 degrees: (-sin t sin p, cos t, sin t cos p).
    const double t = 60.0 * kPiD / 180.0, p = 200.0 * kPiD / 180.0;
    const Vec3 d(glm::dvec3(-std::sin(t) * std::sin(p), std::cos(t), std::sin(t) * std::cos(p)));
    const Ray ray = makeRay(Vec3(0.0f, 0.0f, 5.0f), d);
    const Color got = model == ShadingModel::Physical ? trace(rig, ray, kTermAll) : rig.shade(ray);
    expectColorNear(got, Color(6.0f, 4.0f, 2.0f), 1e-6f, "the bright texel");
  }
}

TEST(EnvironmentLight, MapOverAPlaneConvergesToRhoOverPiTimesIrradiance) {
  // A Lambert plane (rho 0.6) facing +y under a 16 x 8 map (a dim sky and one bright
  // texel above the horizon). Reference: the map's exact irradiance on a +y surface
  // (each pixel's integral of cos theta). The MIS estimate averaged over 256 camera
  // samples x 64 light and 64 BSDF samples; tolerance 2% relative (its standard error,
  // from the spread of the 256 means, is printed and is several times smaller).
  const int w = 16, h = 8;
  std::vector<Color> texels(static_cast<size_t>(w) * h, Color(0.2f));
  texels[2 * w + 5] = Color(40.0f);
  Scene scene = physicalScene();
  scene.render.lightSamples = 64;
  scene.materials.push_back(lambert("plane", Color(0.6f)));
  scene.meshes.push_back(makeQuad(Vec3(-50, 0, -50), Vec3(0, 0, 100), Vec3(100, 0, 0), 0));
  scene.lights.push_back(makeEnvironmentLight(Color(1.0f), 1.0f, makeEnvironmentMap(w, h, texels, 25.0f)));
  double irradiance = 0.0;
  for (int i = 0; i < h / 2; ++i) {
    const double t0 = kPiD * i / h, t1 = kPiD * (i + 1) / h;
    const double band = 0.5 * (std::sin(t1) * std::sin(t1) - std::sin(t0) * std::sin(t0)) * 2.0 * kPiD / w;
    for (int j = 0; j < w; ++j) irradiance += texels[static_cast<size_t>(i) * w + j].r * band;
  }
  const double want = 0.6 / kPiD * irradiance;
  Rig rig(scene);
  const Ray ray = makeRay(Vec3(0.3f, 2.0f, 1.0f), Vec3(-0.2f, -1.0f, -0.4f));
  const auto [mean, se] = meanOverSamples(rig, ray, 256, 5, kTermDirect);
  std::printf("plane under a map: %.5f, want %.5f (standard error %.5f, %.2f%%)\n", mean, want, se,
              100.0 * se / want);
  EXPECT_LT(rel(mean, want), 0.02);
}

}  // namespace
}  // namespace penumbra
