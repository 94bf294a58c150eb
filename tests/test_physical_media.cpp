// The physical model's camera rays and shadow rays through participating media against
// closed forms: Beer–Lambert through a slab, single scattering from a point light in an
// infinite medium (a quadrature of the 1D integral), a clear boundary that changes no
// pixel, counters only for rays that enter a medium, one image for any thread count.
#include "core/media/phase_function.h"
#include "support/media_tracking.h"
#include "support/physical_fixtures.h"
#include "trace/medium_shadow.h"
#include <tbb/global_control.h>

namespace penumbra {
namespace {

// A box boundary (invisible: no material) filled with `medium`, in vacuum.
void addFogBox(Scene& scene, const Vec3& lo, const Vec3& hi, int medium) {
  TriangleMesh box = makeBox(lo, hi, 0);
  box.media = {medium, kNoMedium, true};
  scene.boundaryMeshes.push_back(box);
}

Medium fog(Color sigmaA, Color sigmaS, float g = 0.0f) {
  Medium m = testing::makeMedium(sigmaA, sigmaS, g);
  m.name = "fog";
  return m;
}

// A Lambert plane (rho 0.5) at y = 0, a point light of intensity 2 at (0, 3, 0), and a
// slab y in [1, 2] of a grey-free medium between them.
Scene slabScene() {
  Scene scene = physicalScene();
  scene.materials.push_back(lambert("plane", Color(0.5f)));
  scene.meshes.push_back(makeQuad(Vec3(-50, 0, -50), Vec3(0, 0, 100), Vec3(100, 0, 0), 0));
  scene.lights.push_back(point(Vec3(0.0f, 3.0f, 0.0f), Color(1.0f), 2.0f));
  scene.media.push_back(fog(Color(0.1f, 0.2f, 0.3f), Color(0.2f, 0.3f, 0.6f)));
  addFogBox(scene, Vec3(-20.0f, 1.0f, -20.0f), Vec3(20.0f, 2.0f, 20.0f), 0);
  return scene;
}

// One camera sample as the tile loop shades it (the camera's medium, its first hit).
Color sample(const Rig& rig, const Ray& ray, ThreadState& ts) {
  Hit hit;
  const bool found = rig.tracer.intersect(ray, hit);
  return rig.ctx.choices.integrator->sample(rig.ctx, ray, found ? &hit : nullptr, Aov::Beauty, ts);
}

TEST(PhysicalMedia, ShadowRayThroughAHomogeneousSlabIsBeerLambert) {
  // A shadow ray from the plane straight up to the light crosses the slab over d = 1:
  // exp(-sigma_t d) per channel, within 1e-5 (the closed form; only float rounding).
  const Scene scene = slabScene();
  Rig rig(scene);
  ThreadState ts;
  const Color sigmaT = scene.media[0].sigmaT();
  Ray up = makeRay(Vec3(0.3f, 0.5f, 0.2f), Vec3(0, 1, 0));
  up.tMax = 2.5f;
  const Color t = lightTransmittance(rig.ctx, up, 0.0f, 0, kNoMedium, ts);
  for (int c = 0; c < 3; ++c) EXPECT_NEAR(t[c], std::exp(-sigmaT[c]), 1e-5f) << c;
  EXPECT_EQ(ts.counts.transmittanceRays, 1u);
  // Slanted: the slab's chord is 1 / cos.
  const Vec3 from(1.5f, 0.5f, -0.5f), light(0.0f, 3.0f, 0.0f);
  Ray slant = makeRay(from, light - from);
  slant.tMax = glm::length(light - from);
  const float cosine = 2.5f / slant.tMax;
  const Color ts2 = lightTransmittance(rig.ctx, slant, 0.0f, 0, kNoMedium, ts);
  for (int c = 0; c < 3; ++c) EXPECT_NEAR(ts2[c], std::exp(-sigmaT[c] / cosine), 1e-5f) << c;
}

TEST(PhysicalMedia, LitPlaneUnderASlabIsAttenuatedByItsChord) {
  // The camera ray stays below the slab; the plane's direct light is
  // rho/pi I cos / d^2 x exp(-sigma_t / cos): by the shadow ray, and with shadows off
  // too (the gate's "lit" answer still owes the medium's transmittance). 1e-4 relative.
  const Scene scene = slabScene();
  Rig rig(scene);
  const Vec3 eye(-3.0f, 0.5f, 0.1f), p(0.4f, 0.0f, 0.3f), light(0.0f, 3.0f, 0.0f);
  const double d = glm::length(glm::dvec3(light - p)), cosT = 3.0 / d;
  const Color sigmaT = scene.media[0].sigmaT();
  for (bool shadows : {true, false}) {
    rig.ctx.choices.shadows = shadows;
    ThreadState ts;
    beginSample(ts, 7);
    const Color got = sample(rig, makeRay(eye, p - eye), ts);
    for (int c = 0; c < 3; ++c) {
      const double want = 0.5 / kPiD * 2.0 * cosT / (d * d) * std::exp(-sigmaT[c] / cosT);
      EXPECT_LT(rel(got[c], want), 1e-4) << "shadows " << shadows << " ch " << c << ": " << got[c] << " vs " << want;
    }
    EXPECT_EQ(ts.counts.mediumSegments, 0u);  // the camera ray never enters the slab
  }
}

// Single scattering into a ray (origin o, unit d) from a point light of intensity I at q
// in an infinite homogeneous medium: the integral over t of
// sigma_s exp(-sigma_t t) p(wi . d) I exp(-sigma_t r) / r^2, with t = delta + D tan(theta)
// (smooth in theta: I / r^2 dt = I / D dtheta), by Simpson's rule in double.
double singleScatterQuadrature(const Vec3& o, const Vec3& d, const Vec3& q, double I, double sigmaS,
                               double sigmaT, float g) {
  const glm::dvec3 O(o), Dir(d), Q(q);
  const double delta = glm::dot(Q - O, Dir), D = glm::length(O + delta * Dir - Q);
  const double a = std::atan2(-delta, D), b = kPiD / 2.0;
  const int n = 400000;
  const double h = (b - a) / n;
  auto f = [&](double theta) {
    const double t = delta + D * std::tan(theta);
    if (!std::isfinite(t) || t > 1e6) return 0.0;
    const glm::dvec3 x = O + t * Dir;
    const double r = glm::length(Q - x);
    const double cosine = glm::dot((Q - x) / r, Dir);
    return sigmaS * std::exp(-sigmaT * (t + r)) * henyeyGreenstein(g, static_cast<float>(cosine)) * I / D;
  };
  double sum = f(a) + f(b);
  for (int i = 1; i < n; ++i) sum += f(a + i * h) * (i % 2 ? 4.0 : 2.0);
  return sum * h / 3.0;
}

// The scene is the medium (camera inside it), no surfaces: every camera ray misses and
// sees only the light scattered once into it, here by `volumeSamples` stratified
// samples of each technique (equiangular and distance, under the balance heuristic).
struct ScatterRun {
  glm::dvec3 mean{0.0}, standardError{0.0}, want{0.0};
};

ScatterRun singleScatterRuns(int volumeSamples, int runs) {
  Scene scene = physicalScene();
  scene.media.push_back(fog(Color(0.05f), Color(0.2f, 0.3f, 0.1f), 0.3f));
  scene.sceneMedium = scene.cameraMedium = 0;
  const Vec3 light(0.5f, 1.0f, 0.0f);
  scene.lights.push_back(point(light, Color(1.0f), 4.0f));
  Rig rig(scene);
  rig.ctx.choices.volumeSamples = volumeSamples;
  const Ray ray = makeRay(Vec3(-2.0f, 0.0f, 0.3f), Vec3(1.0f, 0.1f, 0.0f));
  glm::dvec3 sum(0.0), sum2(0.0);
  for (int k = 0; k < runs; ++k) {
    ThreadState ts;
    beginSample(ts, hashKey(99, k));
    const glm::dvec3 v(sample(rig, ray, ts));
    sum += v;
    sum2 += v * v;
  }
  ScatterRun out;
  const Medium& m = scene.media[0];
  for (int c = 0; c < 3; ++c) {
    out.mean[c] = sum[c] / runs;
    out.standardError[c] = std::sqrt(std::max(0.0, sum2[c] / runs - out.mean[c] * out.mean[c]) / runs);
    out.want[c] = singleScatterQuadrature(ray.origin, ray.dir, light, 4.0, m.sigmaS[c], m.sigmaT()[c], m.g);
  }
  return out;
}

TEST(PhysicalMedia, SingleScatteringFromAPointLightMatchesQuadrature) {
  // Mean of 200000 camera samples within 0.5% of the quadrature, and its standard error
  // well below that.
  const ScatterRun r = singleScatterRuns(1, 200000);
  for (int c = 0; c < 3; ++c) {
    EXPECT_LT(rel(r.mean[c], r.want[c]), 0.005)
        << "ch " << c << ": " << r.mean[c] << " vs " << r.want[c] << " (se " << r.standardError[c] << ")";
    EXPECT_LT(r.standardError[c] / r.want[c], 0.0015) << c;
  }
}

TEST(PhysicalMedia, StratifiedVolumeSamplesKeepTheMeanAndCutTheNoise) {
  // render.volume_samples 16 over 12500 camera samples: the same 200000 light samples,
  // the same mean within 0.5%, and a smaller standard error than independent samples
  // give (strata in distance and in the light's numbers never add variance).
  const ScatterRun one = singleScatterRuns(1, 200000), strata = singleScatterRuns(16, 12500);
  for (int c = 0; c < 3; ++c) {
    EXPECT_LT(rel(strata.mean[c], strata.want[c]), 0.005) << "ch " << c << ": " << strata.mean[c] << " vs " << strata.want[c];
    EXPECT_LT(strata.standardError[c], one.standardError[c]) << c;
  }
}

TEST(PhysicalMedia, GlassBallOfAbsorbingFogPassesItsMediumToTheRefractedRay) {
  // A ball of index 1 (no reflection, no bending) filled with an absorbing medium in a
  // white background: the ray through its centre enters the medium at the first
  // surface (mediumBeyond) and leaves it at the second, so it sees exp(-sigma_a 2R).
  Scene scene = physicalScene();
  Material glass = lambert("clear", Color(0.0f));
  glass.transparent = true;
  glass.ior = 1.0f;
  scene.materials.push_back(glass);
  scene.render.background = Color(1.0f);
  scene.media.push_back(fog(Color(0.3f, 0.6f, 0.9f), Color(0.0f)));
  scene.spheres.push_back(Sphere{Vec3(0.0f), 0.75f, 0, {0, kNoMedium, true}});
  Rig rig(scene);
  ThreadState ts;
  beginSample(ts, 3);
  const Color got = sample(rig, makeRay(Vec3(0.0f, 0.0f, 5.0f), Vec3(0, 0, -1)), ts);
  for (int c = 0; c < 3; ++c) EXPECT_NEAR(got[c], std::exp(-scene.media[0].sigmaA[c] * 1.5f), 1e-5f) << c;
  EXPECT_EQ(ts.counts.mediumSegments, 1u);
}

TEST(PhysicalMedia, EmissiveInfiniteMediumGlowsAtSigmaALeOverSigmaT) {
  // No lights, no surfaces: a camera inside an emitting medium sees the integral of
  // exp(-sigma_t t) sigma_a Le over t, sigma_a Le / sigma_t (closed form, 1e-6).
  Scene scene = physicalScene();
  Medium m = fog(Color(0.2f, 0.4f, 0.1f), Color(0.3f));
  m.emission = Color(2.0f, 1.0f, 0.5f);
  scene.media.push_back(m);
  scene.sceneMedium = scene.cameraMedium = 0;
  Rig rig(scene);
  ThreadState ts;
  beginSample(ts, 5);
  const Color got = sample(rig, makeRay(Vec3(0.0f), Vec3(0.3f, 0.2f, -1.0f)), ts);
  for (int c = 0; c < 3; ++c) EXPECT_NEAR(got[c], m.sigmaA[c] * m.emission[c] / m.sigmaT()[c], 1e-6f) << c;
}

TEST(PhysicalMedia, SmallSphereLightScattersAsAPointLightOfEqualIntensity) {
  // A sphere light of radius r and radiance L seen from afar is a point light of
  // intensity L pi r^2: the single scattering into the same camera ray (area light
  // path: the equiangular centre drawn on the light, a light sample per scattering
  // point) within 1% of the point light's, 100000 samples each (standard error ~0.2%);
  // the same with volume_samples 16 (the centre stratified over the light too).
  auto render = [](const Light& light, int volumeSamples = 1) {
    Scene scene = physicalScene();
    scene.media.push_back(fog(Color(0.05f), Color(0.2f), 0.3f));
    scene.sceneMedium = scene.cameraMedium = 0;
    scene.lights.push_back(light);
    Rig rig(scene);
    rig.ctx.choices.volumeSamples = volumeSamples;
    const Ray ray = makeRay(Vec3(-2.0f, 0.0f, 0.3f), Vec3(1.0f, 0.1f, 0.0f));
    double sum = 0.0;
    const int runs = 100000 / volumeSamples;
    for (int k = 0; k < runs; ++k) {
      ThreadState ts;
      beginSample(ts, hashKey(17, k));
      sum += sample(rig, ray, ts).r;
    }
    return sum / runs;
  };
  const Vec3 q(0.5f, 1.0f, 0.0f);
  const float r = 0.02f, intensity = 4.0f;
  Light sphere;
  sphere.type = LightType::Sphere;
  sphere.position = q;
  sphere.radius = r;
  sphere.intensity = intensity / (kPi * r * r);
  const double fromPoint = render(point(q, Color(1.0f), intensity)), fromSphere = render(sphere);
  EXPECT_LT(rel(fromSphere, fromPoint), 0.01) << fromSphere << " vs " << fromPoint;
  const double stratified = render(sphere, 16);
  EXPECT_LT(rel(stratified, fromPoint), 0.01) << stratified << " vs " << fromPoint;
}

// A plane, a ball and a quad light over them, a point light: shading with area samples.
Scene litRoom() {
  Scene scene = physicalScene();
  scene.materials.push_back(lambert("grey", Color(0.6f)));
  scene.meshes.push_back(makeQuad(Vec3(-5, -1, -5), Vec3(0, 0, 10), Vec3(10, 0, 0), 0));
  scene.spheres.push_back(Sphere{Vec3(0.3f, 0.0f, 0.0f), 0.8f, 0, {}});
  scene.lights.push_back(point(Vec3(-1.0f, 3.0f, 1.0f), Color(1.0f, 0.9f, 0.8f), 6.0f));
  scene.lights.push_back(quadLight(Vec3(-0.5f, 2.5f, -0.5f), Vec3(1, 0, 0), Vec3(0, 0, 1), Color(1.0f), 3.0f));
  scene.camera.width = 40;
  scene.camera.height = 30;
  scene.render.packets = false;  // both renders trace ray by ray: no tie between faces decided apart
  return scene;
}

TEST(PhysicalMedia, ClearBoundaryChangesNoPixel) {
  // A boundary box with sigma 0 across camera and shadow rays: the same bytes.
  const Scene plain = litRoom();
  Scene clear = litRoom();
  clear.media.push_back(fog(Color(0.0f), Color(0.0f)));
  addFogBox(clear, Vec3(-1.0f, -2.0f, -1.0f), Vec3(1.5f, 1.5f, 2.0f), 0);
  const Image a = Rig(plain).render(), b = Rig(clear).render();
  ASSERT_EQ(a.pixels.size(), b.pixels.size());
  int differ = 0;
  for (size_t i = 0; i < a.pixels.size(); ++i) differ += a.pixels[i] != b.pixels[i];
  EXPECT_EQ(differ, 0);
}

TEST(PhysicalMedia, RayMissingTheSmallBoxCountsNothing) {
  // A small fog box off to the side: a camera ray (and its shadow rays) that never
  // enters it adds no medium counter; one through it does.
  Scene scene = litRoom();
  scene.lights.resize(1);  // the point light only: its shadow rays stay clear of the box
  scene.media.push_back(fog(Color(0.2f), Color(0.5f)));
  addFogBox(scene, Vec3(2.0f, -1.0f, 2.0f), Vec3(2.5f, -0.5f, 2.5f), 0);
  Rig rig(scene);
  ThreadState miss;
  beginSample(miss, 1);
  const Vec3 eye(0.0f, 1.0f, 5.0f);
  EXPECT_GT(maxComponent(sample(rig, makeRay(eye, Vec3(-2.0f, -1.0f, 0.0f) - eye), miss)), 0.0f);
  EXPECT_EQ(miss.counts.mediumSegments, 0u);
  EXPECT_EQ(miss.counts.mediumSamples, 0u);
  EXPECT_EQ(miss.counts.transmittanceRays, 0u);
  EXPECT_EQ(miss.counts.volumeGathers, 0u);
  ThreadState through;
  beginSample(through, 1);
  sample(rig, makeRay(eye, Vec3(2.25f, -0.75f, 2.25f) - eye), through);
  EXPECT_EQ(through.counts.mediumSegments, 1u);
  EXPECT_GT(through.counts.mediumSamples, 0u);
}

TEST(PhysicalMedia, FogRendersTheSameForOneAndTwoThreads) {
  // Scene fog, a denser box in it, area and point lights, 2 samples per pixel.
  Scene scene = litRoom();
  scene.render.packets = true;
  scene.camera.spp = 2;
  scene.media.push_back(fog(Color(0.02f), Color(0.08f), 0.4f));
  scene.media.push_back(fog(Color(0.1f), Color(0.6f), -0.2f));
  scene.sceneMedium = scene.cameraMedium = 0;
  scene.spheres[0].media = {kNoMedium, 0, true};
  addFogBox(scene, Vec3(-2.0f, -1.0f, -1.0f), Vec3(-0.8f, 1.0f, 1.0f), 1);
  scene.boundaryMeshes[0].media.outside = 0;
  Image images[2];
  RayCounts counts[2];
  for (int threads : {1, 2}) {
    tbb::global_control limit(tbb::global_control::max_allowed_parallelism, threads);
    Rig rig(scene);
    RenderOptions options;
    images[threads - 1] = renderImage(rig.ctx, options, counts[threads - 1]);
  }
  int differ = 0;
  for (size_t i = 0; i < images[0].pixels.size(); ++i) differ += images[0].pixels[i] != images[1].pixels[i];
  EXPECT_EQ(differ, 0);
  EXPECT_EQ(counts[0].mediumSegments, counts[1].mediumSegments);
  EXPECT_EQ(counts[0].mediumSamples, counts[1].mediumSamples);
  EXPECT_GT(counts[0].mediumSegments, static_cast<uint64_t>(scene.camera.width * scene.camera.height));
  for (const Color& c : images[0].pixels) EXPECT_TRUE(isFinite(c));
}

TEST(PhysicalMedia, ExtremeMediaKeepEveryPixelFinite) {
  // sigma 1e30 (opaque fog), g = +-0.999999 (a needle lobe) and sigma 0 side by side in
  // the scene fog: no sample NaN or infinite, no pixel negative.
  for (float g : {0.999999f, -0.999999f}) {
    Scene scene = litRoom();
    scene.media.push_back(fog(Color(0.01f), Color(0.3f), g));
    scene.media.push_back(fog(Color(1e30f), Color(1e30f), g));
    scene.media.push_back(fog(Color(0.0f), Color(0.0f), g));
    scene.sceneMedium = scene.cameraMedium = 0;
    addFogBox(scene, Vec3(-2.0f, -1.0f, -1.0f), Vec3(-0.8f, 1.0f, 1.0f), 1);
    addFogBox(scene, Vec3(0.8f, -1.0f, -1.0f), Vec3(2.0f, 1.0f, 1.0f), 2);
    for (TriangleMesh& box : scene.boundaryMeshes.edit()) box.media.outside = 0;
    Rig rig(scene);
    RayCounts counts;
    const Image image = renderImage(rig.ctx, RenderOptions{}, counts);
    EXPECT_EQ(counts.nonfiniteSamples, 0u) << "g " << g;  // the pixel sums drop those: count them
    int bad = 0;
    for (const Color& c : image.pixels) bad += !isFinite(c) || c.r < 0.0f || c.g < 0.0f || c.b < 0.0f;
    EXPECT_EQ(bad, 0) << "g " << g;
  }
}

}  // namespace
}  // namespace penumbra
