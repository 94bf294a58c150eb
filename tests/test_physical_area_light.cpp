// Quad and sphere area lights against closed-form radiometry: the irradiance of a
// Lambertian rectangle on a parallel plane (the point-to-rectangle form factor), of a
// sphere straight above (bare, and with a ball just below it), the emitter seen by the
// camera on its emitting side only, photons that leave from the surface into its
// hemisphere, and byte-identical renders at 1 and 2 threads in both models.
#include "support/form_factor.h"
#include "plan/pipeline.h"
#include "core/error.h"
#include "core/light_sample.h"
#include "io/scene_loader.h"
#include "io/scene_sections.h"
#include "support/physical_fixtures.h"
#include <cstring>
#include <fstream>

namespace penumbra {
namespace {

using testing::rectFactor;

TEST(AreaLight, QuadIrradianceOnAParallelPlaneMatchesTheFormFactor) {
  // A 1.0 x 0.8 quad light of radiance L at height 1.2, emitting downwards, over a
  // Lambert plane (rho 0.5): L_out = rho L F. Tolerance 1% (the issue's), with 1024
  // stratified samples per point; the plane is reached from an eye below the light.
  Scene scene = physicalScene();
  scene.materials.push_back(lambert("plane", Color(0.5f)));
  scene.meshes.push_back(makeQuad(Vec3(-50, 0, -50), Vec3(0, 0, 100), Vec3(100, 0, 0), 0));
  const float a = 1.0f, b = 0.8f, h = 1.2f;
  const Color colour(1.0f, 0.9f, 0.7f);
  scene.lights.push_back(quadLight(Vec3(-a / 2, h, -b / 2), Vec3(a, 0, 0), Vec3(0, 0, b), colour, 3.0f));
  scene.render.lightSamples = 1024;
  addEmitters(scene);
  Rig rig(scene);
  const Vec3 eye(-2.0f, 0.9f, 1.5f);
  for (Vec3 p : {Vec3(0.0f), Vec3(0.3f, 0.0f, 0.2f), Vec3(1.1f, 0.0f, -0.6f), Vec3(-2.5f, 0.0f, 0.4f)}) {
    const Color got = trace(rig, makeRay(eye, p - eye), kTermDirect);
    const double F = rectFactor(-a / 2 - p.x, a / 2 - p.x, -b / 2 - p.z, b / 2 - p.z, h);
    for (int c = 0; c < 3; ++c) {
      const double want = 0.5 * colour[c] * 3.0 * F;
      EXPECT_LT(rel(got[c], want), 0.01) << "at (" << p.x << "," << p.z << "): " << got[c] << " vs " << want;
    }
  }
  // Behind the light (above it) nothing arrives: it emits on one side.
  EXPECT_EQ(sampleLight(scene.lights[0], Vec3(0, 2, 0), 0.3f, 0.6f).valid, false);
}

// A sphere light of radius 0.5 and radiance 4 centred 2 above the origin.
Light sphereAboveTheOrigin() {
  Light s;
  s.type = LightType::Sphere;
  s.position = Vec3(0.0f, 2.0f, 0.0f);
  s.radius = 0.5f;
  s.intensity = 4.0f;
  return s;
}

// A Lambert plane (rho 0.8) at y = 0 under `light`, sampled `samples` times a point.
Scene underASphereLight(const Light& light, int samples) {
  Scene scene = physicalScene();
  scene.materials.push_back(lambert("plane", Color(0.8f)));
  scene.meshes.push_back(makeQuad(Vec3(-50, 0, -50), Vec3(0, 0, 100), Vec3(100, 0, 0), 0));
  scene.lights.push_back(light);
  scene.render.lightSamples = samples;
  return scene;
}

TEST(AreaLight, SphereAboveAPointGivesPiLSin2) {
  // A sphere light of radius R whose centre is at distance d straight above the
  // point: E = pi L (R / d)^2, so L_out = rho L (R / d)^2. Cone sampling of the
  // subtended directions; tolerance 1% with 256 samples.
  const Light s = sphereAboveTheOrigin();
  Scene scene = underASphereLight(s, 256);
  addEmitters(scene);
  Rig rig(scene);
  const Vec3 eye(-1.5f, 1.0f, 1.0f);
  const Color got = trace(rig, makeRay(eye, Vec3(0.0f) - eye), kTermDirect);
  EXPECT_LT(rel(got.x, 0.8 * 4.0 * (0.5 * 0.5) / (2.0 * 2.0)), 0.01) << got.x;
  // The camera sees the sphere's own radiance; lightPower is pi A L.
  EXPECT_NEAR(trace(rig, makeRay(eye, s.position - eye), kTermAll).x, 4.0f, 1e-6f);
  EXPECT_NEAR(lightPower(s, SceneSphere{}).x, kPi * 4.0f * kPi * 0.25f * 4.0f, 1e-3f);
}

TEST(AreaLight, AnOccluderJustBelowASphereLightHidesItsCap) {
  // A ball of radius 0.2 whose top is 2 cm below a sphere light of radius 0.5 at
  // height 2 hides, from the point below both, the cap within asin(0.2 / 1.28) of
  // the axis: E = pi L (sin^2 a_light - sin^2 a_ball). The ball's cone lies inside the
  // light's, and every ray in it meets the ball before the light.
  Scene scene = underASphereLight(sphereAboveTheOrigin(), 1024);
  scene.spheres.push_back(Sphere{Vec3(0.0f, 1.28f, 0.0f), 0.2f, 0});
  addEmitters(scene);
  Rig rig(scene);
  const Vec3 eye(-1.5f, 1.0f, 1.0f);
  const Color got = trace(rig, makeRay(eye, Vec3(0.0f) - eye), kTermDirect);
  const double ball = 0.2 / 1.28;
  EXPECT_LT(rel(got.x, 0.8 * 4.0 * (0.25 / 4.0 - ball * ball)), 0.01) << got.x;
}

TEST(AreaLight, ClosedFormIrradianceMatchesTheFormFactorAndSampling) {
  // Lambert's polygon formula against the analytic form factor (parallel plane),
  // and, for tilted normals whose horizon cuts the quad, against 256^2 stratified
  // samples of L cos over the light. Tolerance 1e-4 (analytic) and 0.2% (sampled).
  const float a = 1.0f, b = 0.8f, h = 1.2f;
  const Light q = quadLight(Vec3(-a / 2, h, -b / 2), Vec3(a, 0, 0), Vec3(0, 0, b), Color(1.0f), 3.0f);
  Color E;
  const Vec3 p(0.3f, 0.0f, 0.2f);
  ASSERT_TRUE(unoccludedIrradiance(prepareLight(q, p), Vec3(0, 1, 0), Vec3(0, 1, 0), E));
  const double F = rectFactor(-a / 2 - p.x, a / 2 - p.x, -b / 2 - p.z, b / 2 - p.z, h);
  EXPECT_LT(rel(E.x, 3.0 * kPiD * F), 1e-4) << E.x;
  for (Vec3 n : {glm::normalize(Vec3(1, 0.3f, 0)), glm::normalize(Vec3(0.2f, 1, -0.7f)), Vec3(0, 0, 1)}) {
    const LightSampler sampler = prepareLight(q, Vec3(0.1f, 0.9f, 0.0f));
    ASSERT_TRUE(unoccludedIrradiance(sampler, n, n, E));
    double sum = 0.0;
    const int side = 256;
    for (int i = 0; i < side; ++i)
      for (int j = 0; j < side; ++j) {
        LightIncidence in = sampleLight(sampler, (i + 0.5f) / side, (j + 0.5f) / side);
        if (in.valid) sum += in.radiance.x * std::max(0.0f, glm::dot(n, in.wi));
      }
    EXPECT_LT(rel(E.x, sum / (side * side)), 2e-3) << n.x << "," << n.y << "," << n.z;
  }
  // Behind the emitting side: none, but answered.
  ASSERT_TRUE(unoccludedIrradiance(prepareLight(q, Vec3(0, 2, 0)), Vec3(0, -1, 0), Vec3(0, -1, 0), E));
  EXPECT_EQ(E, Color(0.0f));
  // A sphere above the horizon: pi L sin^2 cos; cut by the horizon: no closed form.
  Light s;
  s.type = LightType::Sphere;
  s.position = Vec3(1.0f, 2.0f, 0.0f);
  s.radius = 0.5f;
  s.intensity = 2.0f;
  const LightSampler ss = prepareLight(s, Vec3(0.0f));
  ASSERT_TRUE(unoccludedIrradiance(ss, Vec3(0, 1, 0), Vec3(0, 1, 0), E));
  EXPECT_LT(rel(E.x, kPiD * 2.0 * (0.25 / 5.0) * (2.0 / std::sqrt(5.0))), 1e-5);
  EXPECT_FALSE(unoccludedIrradiance(ss, glm::normalize(Vec3(-2, 1, 0)), glm::normalize(Vec3(-2, 1, 0)), E));
  // A geometric normal whose horizon cuts the sphere also forbids the closed form.
  EXPECT_FALSE(unoccludedIrradiance(ss, Vec3(0, 1, 0), glm::normalize(Vec3(-2, 1, 0)), E));
}

TEST(AreaLight, SmallAndDistantLightsKeepTheirPrecision) {
  // A 1 cm quad 10 m away, 60 degrees off the normal: the edge angles are ~1e-3 rad,
  // where acos loses them; E ~ L A cos / d^2. And a sphere with r / d = 1e-4, where
  // 1 - cos(theta_max) cancels in float: E = pi L (r / d)^2 cos, and samples see it.
  const Vec3 n(0, 1, 0);
  const float d = 10.0f, side = 0.01f, c60 = 0.5f, s60 = std::sqrt(3.0f) / 2;
  const Vec3 centre = d * Vec3(s60, c60, 0.0f);
  const Light q = quadLight(centre - Vec3(side / 2, 0, side / 2), Vec3(side, 0, 0), Vec3(0, 0, side),
                            Color(1.0f), 1.0f);  // faces down (edge1 x edge2 = -y)
  Color E;
  ASSERT_TRUE(unoccludedIrradiance(prepareLight(q, Vec3(0.0f)), n, n, E));
  // Solid angle ~ A cos_l / d^2 with cos_l = cos 60 (the light faces down), times cos 60 at p.
  const double want = side * side * c60 / (d * d) * c60;
  EXPECT_LT(rel(E.x, want), 2e-3) << E.x << " vs " << want;
  Light s;
  s.type = LightType::Sphere;
  s.position = Vec3(0.0f, 1000.0f, 0.0f);
  s.radius = 0.1f;
  const LightSampler ss = prepareLight(s, Vec3(0.0f));
  ASSERT_TRUE(unoccludedIrradiance(ss, n, n, E));
  EXPECT_LT(rel(E.x, kPiD * 1e-8), 1e-3) << E.x;
  const LightIncidence in = sampleLight(ss, 0.3f, 0.7f);
  ASSERT_TRUE(in.valid);
  EXPECT_LT(rel(in.radiance.x * in.wi.y, kPiD * 1e-8), 1e-3);  // one sample: L / pdf x cos
  EXPECT_GE(in.distance, 999.89f);  // on the near side of the sphere
  EXPECT_LE(in.distance, 1000.0f);
}

TEST(AreaLight, QuadGlowsOnItsEmittingSideOnly) {
  Scene scene = physicalScene();
  scene.lights.push_back(quadLight(Vec3(-1, 1, -1), Vec3(2, 0, 0), Vec3(0, 0, 2), Color(1.0f), 2.5f));
  addEmitters(scene);
  Rig rig(scene);
  EXPECT_EQ(trace(rig, makeRay(Vec3(0, 0, 0), Vec3(0, 1, 0)), kTermAll), Color(2.5f));  // from below
  EXPECT_EQ(trace(rig, makeRay(Vec3(0, 3, 0), Vec3(0, -1, 0)), kTermAll), Color(0.0f));  // from above
}

TEST(AreaLight, PhotonsLeaveTheSurfaceIntoItsHemisphere) {
  const Light q = quadLight(Vec3(-1, 1, -1), Vec3(2, 0, 0), Vec3(0, 0, 2), Color(1.0f), 1.0f);
  Rng rng(3);
  double cosSum = 0.0;
  const int n = 20000;
  for (int i = 0; i < n; ++i) {
    PhotonRay r = sampleLightPhoton(q, SceneSphere{}, rng.uniform(), rng.uniform(), rng.uniform(), rng.uniform());
    ASSERT_NEAR(r.origin.y, 1.0f, 1e-6f);
    ASSERT_LE(std::abs(r.origin.x), 1.0f);
    ASSERT_LT(r.dir.y, 0.0f);  // downwards: the emitting side
    cosSum += -r.dir.y;
  }
  EXPECT_NEAR(cosSum / n, 2.0 / 3.0, 0.01);  // cosine-weighted: E[cos] = 2/3
}

TEST(AreaLight, LoaderTakesRadianceOrPowerNotBoth) {
  const std::string head = R"({"camera": {"width": 8, "height": 8}, "lights": [)";
  const std::string tail = R"(], "objects": [{"type": "sphere", "center": [0, 0, 0], "radius": 1}]})";
  Scene s = parseScene(head + R"({"type": "quad", "corner": [0, 2, 0], "edge1": [2, 0, 0],
                       "edge2": [0, 0, 1], "power": 10})" + tail, "a.json", {});
  ASSERT_EQ(s.lights.size(), 1u);
  EXPECT_NEAR(s.lights[0].intensity, 10.0f / (kPi * 2.0f), 1e-5f);
  EXPECT_EQ(s.meshes.size(), 1u);  // the emitter's own surface joined the scene
  EXPECT_THROW(parseScene(head + R"({"type": "quad", "corner": [0, 2, 0], "edge1": [2, 0, 0],
                          "edge2": [0, 0, 1], "power": 10, "radiance": 2})" + tail, "b.json", {}),
               InputError);
  EXPECT_THROW(parseScene(head + R"({"type": "quad", "corner": [0, 2, 0], "edge1": [2, 0, 0],
                          "edge2": [4, 0, 0]})" + tail, "c.json", {}),
               InputError);
  EXPECT_THROW(parseScene(head + R"({"type": "sphere", "center": [0, 2, 0], "radius": 0})" + tail,
                          "d.json", {}),
               InputError);
}

const char* kSoftScene = R"({
  "camera": {"position": [0, 1.2, 3.2], "look_at": [0, 0.5, 0], "width": 48, "height": 32, "spp": 2},
  "lights": [
    {"type": "quad", "corner": [-0.4, 1.9, -0.4], "edge1": [0.8, 0, 0], "edge2": [0, 0, 0.8],
     "color": [1, 0.9, 0.8], "power": 6},
    {"type": "sphere", "center": [0.9, 1.2, 0.6], "radius": 0.15, "radiance": 8}
  ],
  "materials": {"white": {"ambient": 0.05, "diffuse": 0.7, "p_r": 0.5}},
  "objects": [
    {"type": "quad", "corner": [-2, 0, 2], "edge1": [4, 0, 0], "edge2": [0, 0, -4], "material": "white"},
    {"type": "sphere", "center": [0, 0.4, 0], "radius": 0.4, "material": "white"}
  ],
  "render": {"light_samples": 9},
  "photons": {"shadow": 20000, "indirect": 20000, "global": 20000, "caustic": 0, "gate": "on"}
})";

TEST(AreaLight, RendersAreIdenticalForOneAndTwoThreadsInBothModels) {
  const std::string path = ::testing::TempDir() + "/area_lights.json";
  { std::ofstream(path) << kSoftScene; }
  for (const char* model : {"classic", "physical"}) {
    for (const char* lookup : {"exact", "precomputed"}) {
      RenderRequest req;
      req.scenePath = path;
      req.overrides = {std::string("render.model=") + model, std::string("photons.lookup=") + lookup};
      req.session.threads = 1;
      RenderResult one = runRender(req);
      req.session.threads = 2;
      RenderResult two = runRender(req);
      ASSERT_EQ(one.image.pixels.size(), two.image.pixels.size());
      EXPECT_EQ(std::memcmp(one.image.pixels.data(), two.image.pixels.data(),
                            one.image.pixels.size() * sizeof(Color)), 0) << model << " " << lookup;
      EXPECT_GT(one.stats.rays.gateQueries, 0u) << model;  // area lights have shadow photons
      float hi = 0.0f;
      for (const Color& c : one.image.pixels) {
        ASSERT_TRUE(isFinite(c));
        hi = std::max(hi, maxComponent(c));
      }
      EXPECT_GT(hi, 0.1f) << model;
    }
  }
}

}  // namespace
}  // namespace penumbra
