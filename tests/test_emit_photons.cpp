// The indirect photon pass against counting arguments: Russian-roulette path lengths
// (geometric: 1/(1-p) and p/(1-p) stored per photon), cosine-weighted bounces, the
// walls' colour on survivors, budget splitting, and byte-identical maps for 1 and 2
// threads.
#include "emit/budget.h"
#include "support/emit_fixtures.h"
#include "emit/emit.h"
#include "support/emit_box.h"
#include <gtest/gtest.h>
#include <tbb/global_control.h>
#include <cmath>
#include <cstring>
#include <limits>

namespace penumbra {
namespace {

using testing::boxScene;
using testing::expectWithinSigmas;
using testing::pointLight;
using testing::wallMaterial;

TEST(EmitIndirect, RussianRouletteClassicStoresEveryHit) {
  for (float p : {0.25f, 0.5f}) {
    const uint64_t n = 20000;
    Scene scene = boxScene(1.0f, Vec3(0.1f, 0.2f, -0.3f), 0, n, p);
    scene.photons.maxBounces = 1000;
    scene.photons.estimator = IndirectEstimator::Classic;
    scene.photons.sampling = HemisphereSampling::Cosine;  // unweighted bounces: power stays put
    TraceScene tracer(scene);
    EmittedPhotons maps = emitPhotons(scene, tracer, sceneEmit(scene));
    EXPECT_TRUE(maps.batches.get<MapKind::Shadow>().empty());
    EXPECT_EQ(maps.emitted[MapKind::Indirect], n);
    // Hits per path: 1 + Geometric(p), mean 1/(1-p), variance p/(1-p)^2.
    const double mean = n / (1.0 - p), sd = std::sqrt(n * p) / (1.0 - p);
    expectWithinSigmas(static_cast<double>(maps.batches.get<MapKind::Indirect>().size()), mean, sd, 4.0,
                       "classic, p=" + std::to_string(p));
    // With cosine sampling grey walls keep every photon at the emitted share of
    // the flux 4 pi I / n.
    // The stored power is shared-exponent RGB: within 2^-8 of its largest channel
    // (here every channel) of the float power, which is within the old 1e-4 of the
    // flux share; equal channels stay equal.
    const float power = 4.0f * kPi / n;
    for (const IndirectPhoton& ph : maps.batches.get<MapKind::Indirect>()) {
      const Color stored = ph.power.color();
      ASSERT_NEAR(stored.r, power, power * (1e-4f + 0x1p-8f));
      ASSERT_EQ(stored.r, stored.g);
      ASSERT_EQ(stored.r, stored.b);
      // The stored normal faces where the photon came from.
      EXPECT_LT(glm::dot(decodeOctahedral(ph.normal), decodeOctahedral(ph.direction)), 0.0f);
      EXPECT_NEAR(maxComponent(glm::abs(ph.position)), 1.0f, 1e-5f);
    }
    EXPECT_FLOAT_EQ(maps.classicScale, static_cast<float>(n / (4.0 * kPi)));
  }
}

TEST(EmitIndirect, RussianRouletteDensitySkipsTheFirstHit) {
  const float p = 0.5f;
  const uint64_t n = 20000;
  Scene scene = boxScene(1.0f, Vec3(0.1f, 0.2f, -0.3f), 0, n, p);
  scene.photons.maxBounces = 1000;
  scene.photons.estimator = IndirectEstimator::Density;
  TraceScene tracer(scene);
  EmittedPhotons maps = emitPhotons(scene, tracer, sceneEmit(scene));
  const double mean = n * p / (1.0 - p), sd = std::sqrt(n * p) / (1.0 - p);
  expectWithinSigmas(static_cast<double>(maps.batches.get<MapKind::Indirect>().size()), mean, sd, 4.0, "density");
  // max_bounces caps the path: with 1 bounce at most one stored photon per path,
  // and exactly the survivors of the first roulette, Binomial(n, p).
  scene.photons.maxBounces = 1;
  EmittedPhotons capped = emitPhotons(scene, tracer, sceneEmit(scene));
  expectWithinSigmas(static_cast<double>(capped.batches.get<MapKind::Indirect>().size()), n * p, std::sqrt(n * p * (1 - p)), 4.0,
                     "density, max_bounces 1");
}

// Uniform hemisphere bounces carry the weight 2 cos(theta), which averages 1:
// energy is conserved on average, and the weight follows the bounce direction.
TEST(EmitIndirect, UniformBouncesAreCosineWeighted) {
  const uint64_t n = 40000;
  Scene scene = boxScene(1.0f, Vec3(0.0f), 0, n, 0.5f);
  scene.photons.maxBounces = 1;
  scene.photons.sampling = HemisphereSampling::Uniform;
  TraceScene tracer(scene);
  EmittedPhotons maps = emitPhotons(scene, tracer, sceneEmit(scene));
  const double p0 = 4.0 * kPi / n;
  double sum = 0.0, sum2 = 0.0;
  size_t second = 0;
  // Stored powers are within 2^-8 of their largest channel (shared-exponent RGB; grey
  // here) of the float power, itself within the old 1e-4: a first hit decodes within
  // p0 tol of p0, a weight w within w tol of its own. The window drops bounced photons
  // with |w - 1| < tol too: w is uniform on [0, 2], so that removes 0.4% of them,
  // symmetrically about the mean 1.
  const double tol = 1e-4 + 0x1p-8;
  for (const IndirectPhoton& ph : maps.batches.get<MapKind::Indirect>()) {
    const Color stored = ph.power.color();
    if (std::abs(stored.r - p0) <= p0 * tol && std::abs(stored.g - p0) <= p0 * tol) continue;
    // A bounced photon: weight = power / p0 = 2 cos(theta) in [0, 2].
    double w = stored.r / p0;
    ASSERT_GE(w, 0.0);
    ASSERT_LE(w, 2.0 * (1.0 + tol));
    sum += w;
    sum2 += w * w;
    ++second;
  }
  ASSERT_GT(second, 1000u);
  // Mean of 2 cos(theta) for theta uniform over the hemisphere is 1, variance 1/3.
  expectWithinSigmas(sum / second, 1.0, std::sqrt(1.0 / 3.0 / second), 4.0, "mean uniform weight");
}

TEST(EmitIndirect, SurvivorsTakeOnTheWallColour) {
  // Diffuse (0.9, 0.6, 0.3): a survivor's power is multiplied by colour / max(colour)
  // = (1, 2/3, 1/3), so no channel ever gains (the energy rule, docs/photon-maps.md).
  const uint64_t n = 5000;
  Scene scene = boxScene(1.0f, Vec3(0.0f), 0, n, 0.5f);
  scene.materials[0].diffuse = Color(0.9f, 0.6f, 0.3f);
  scene.photons.maxBounces = 1000;
  scene.photons.sampling = HemisphereSampling::Cosine;
  TraceScene tracer(scene);
  EmittedPhotons maps = emitPhotons(scene, tracer, sceneEmit(scene));
  const float p0 = 4.0f * kPi / n;
  size_t firstHits = 0, secondHits = 0;
  // The stored power is shared-exponent RGB: every channel within 2^-8 of the largest
  // (red, p0) of the float power (itself within the old 1e-4 of the analytic value),
  // an absolute p0 2^-8 for green and blue too, so a deep bounce's green (2/3)^k and
  // blue (1/3)^k fade into that rounding rather than keep 1e-3 relative. The bounce
  // count k is the one whose colour the stored power matches; it is unambiguous for
  // the first hits (k = 0, 1, 2 differ by > 0.1 p0).
  const double tol = p0 * (1e-4 + 0x1p-8);
  for (const IndirectPhoton& ph : maps.batches.get<MapKind::Indirect>()) {
    const Color stored = ph.power.color();
    ASSERT_NEAR(stored.r, p0, tol);
    int k = 0;  // bounces before this hit
    double bestErr = kInf;
    for (int j = 0; j <= 64; ++j) {
      double err = std::max(std::abs(stored.g - p0 * std::pow(2.0 / 3.0, j)),
                            std::abs(stored.b - p0 * std::pow(1.0 / 3.0, j)));
      if (err < bestErr) {
        bestErr = err;
        k = j;
      }
    }
    ASSERT_NEAR(stored.g, p0 * std::pow(2.0 / 3.0, k), tol) << "k = " << k;
    ASSERT_NEAR(stored.b, p0 * std::pow(1.0 / 3.0, k), tol) << "k = " << k;
    firstHits += k == 0;
    secondHits += k == 1;
  }
  EXPECT_EQ(firstHits, n);
  expectWithinSigmas(secondHits, n * 0.5, std::sqrt(n * 0.25), 4.0, "second hits");
}

TEST(Emit, ByteIdenticalForOneAndTwoThreads) {
  Scene scene = boxScene(2.0f, Vec3(0.0f, 1.0f, 0.0f), 30000, 20000, 0.6f);
  scene.materials[0].diffuse = Color(0.7f, 0.5f, 0.3f);
  Material glass;
  glass.name = "glass";
  glass.transparent = true;
  glass.pR = 0.1f;
  glass.pT = 0.8f;
  glass.tint = Color(0.9f, 1.0f, 0.8f);
  scene.materials.push_back(glass);
  scene.spheres.push_back(Sphere{Vec3(0.5f, -0.5f, 0.0f), 0.6f, 1});
  scene.spheres.push_back(Sphere{Vec3(-0.8f, 0.0f, 0.5f), 0.4f, 0});
  scene.lights.push_back(pointLight(Vec3(-1.0f, -1.0f, 1.0f), 2.0f, Color(1.0f, 0.5f, 0.5f)));
  TraceScene tracer(scene);
  EmitOptions options;
  options.batchSize = 512;  // dozens of batches, so both threads get work
  auto run = [&](int threads) {
    tbb::global_control limit(tbb::global_control::max_allowed_parallelism, threads);
    return emitPhotons(scene, tracer, sceneEmit(scene, options));
  };
  EmittedPhotons one = run(1), two = run(2), again = run(2);
  EXPECT_GT(one.batches.get<MapKind::Shadow>().size(), 30000u);  // the spheres cast shadow photons
  EXPECT_GT(one.batches.get<MapKind::Indirect>().size(), 20000u);
  for (const EmittedPhotons* m : {&two, &again}) {
    ASSERT_EQ(m->batches.get<MapKind::Shadow>().size(), one.batches.get<MapKind::Shadow>().size());
    ASSERT_EQ(m->batches.get<MapKind::Indirect>().size(), one.batches.get<MapKind::Indirect>().size());
    EXPECT_EQ(std::memcmp(m->batches.get<MapKind::Shadow>().flatten().data(), one.batches.get<MapKind::Shadow>().flatten().data(),
                          one.batches.get<MapKind::Shadow>().size() * sizeof(ShadowPhoton)), 0);
    EXPECT_EQ(std::memcmp(m->batches.get<MapKind::Indirect>().flatten().data(), one.batches.get<MapKind::Indirect>().flatten().data(),
                          one.batches.get<MapKind::Indirect>().size() * sizeof(IndirectPhoton)), 0);
    EXPECT_EQ(m->emitted[MapKind::Shadow], one.emitted[MapKind::Shadow]);
    EXPECT_EQ(m->classicScale, one.classicScale);
  }
  // Each light's lines all start with one direct hit: its share of the budget.
  size_t perLight[2] = {0, 0};
  for (const ShadowPhoton& p : one.batches.get<MapKind::Shadow>()) {
    if (!p.shadow) ++perLight[p.light];
  }
  std::vector<uint64_t> split = splitBudget(scene, 30000);
  EXPECT_EQ(perLight[0], split[0]);
  EXPECT_EQ(perLight[1], split[1]);
  // A different seed gives different photons.
  scene.render.seed = 999;
  EmittedPhotons other = run(2);
  EXPECT_TRUE(other.batches.get<MapKind::Shadow>().size() != one.batches.get<MapKind::Shadow>().size() ||
              std::memcmp(other.batches.get<MapKind::Shadow>().flatten().data(), one.batches.get<MapKind::Shadow>().flatten().data(),
                          one.batches.get<MapKind::Shadow>().size() * sizeof(ShadowPhoton)) != 0);
}

TEST(SplitBudget, ProportionalToLuminanceAndExact) {
  Scene scene;
  scene.lights = {pointLight(Vec3(0.0f), 1.0f), pointLight(Vec3(0.0f), 2.0f), pointLight(Vec3(0.0f), 3.0f)};
  Light sun;
  sun.type = LightType::Directional;
  sun.intensity = 100.0f;
  scene.lights.push_back(sun);
  // 1000 * (1, 2, 3) / 6 = 166.67, 333.33, 500: the leftover unit goes to the largest remainder.
  EXPECT_EQ(splitBudget(scene, 1000), (std::vector<uint64_t>{167, 333, 500, 0}));
  // Equal thirds of 7: 2.33 each, the tie goes to the lowest index.
  Scene equal;
  equal.lights = {pointLight(Vec3(0.0f)), pointLight(Vec3(1.0f)), pointLight(Vec3(2.0f))};
  EXPECT_EQ(splitBudget(equal, 7), (std::vector<uint64_t>{3, 2, 2}));
  EXPECT_EQ(splitBudget(equal, 0), (std::vector<uint64_t>{0, 0, 0}));
  // Coloured lights split by luminance (0.2126 R + 0.7152 G + 0.0722 B).
  Scene coloured;
  coloured.lights = {pointLight(Vec3(0.0f), 1.0f, Color(1, 0, 0)), pointLight(Vec3(0.0f), 1.0f, Color(0, 1, 0)),
                     pointLight(Vec3(0.0f), 1.0f, Color(0, 0, 1)), pointLight(Vec3(0.0f), 0.0f)};
  for (uint64_t total : {1ull, 10ull, 997ull, 123457ull}) {
    std::vector<uint64_t> c = splitBudget(coloured, total);
    ASSERT_EQ(c.size(), 4u);
    EXPECT_EQ(c[0] + c[1] + c[2] + c[3], total);
    EXPECT_EQ(c[3], 0u);  // zero intensity
    const double w[3] = {0.2126, 0.7152, 0.0722};
    for (int i = 0; i < 3; ++i) EXPECT_NEAR(static_cast<double>(c[i]), total * w[i], 1.0) << total;
  }
  // Only directional lights: nobody gets photons, and none are emitted.
  Scene sunOnly;
  sunOnly.materials.push_back(wallMaterial(0.5f));
  sunOnly.meshes.push_back(makeBox(Vec3(-1.0f), Vec3(1.0f), 0));
  sunOnly.lights = {sun, sun};
  sunOnly.photons.shadowPhotons = 1000;
  sunOnly.photons.indirectPhotons = 1000;
  EXPECT_EQ(splitBudget(sunOnly, 1000), (std::vector<uint64_t>{0, 0}));
  TraceScene tracer(sunOnly);
  EmittedPhotons maps = emitPhotons(sunOnly, tracer, sceneEmit(sunOnly));
  EXPECT_TRUE(maps.batches.get<MapKind::Shadow>().empty());
  EXPECT_TRUE(maps.batches.get<MapKind::Indirect>().empty());
  EXPECT_EQ(maps.emitted[MapKind::Shadow], 0u);
  EXPECT_EQ(maps.emitted[MapKind::Indirect], 0u);
}

// A light whose weight overflowed (inf) or is undefined (NaN) gets nothing; the others
// still share the whole budget exactly. (UBSan: a NaN share cast to uint64 is undefined.)
TEST(SplitBudget, NonFiniteWeightsGetNoPhotons) {
  const double inf = std::numeric_limits<double>::infinity(), nan = std::nan("");
  EXPECT_EQ(splitByWeight({1.0, inf, 3.0}, 100), (std::vector<uint64_t>{25, 0, 75}));
  EXPECT_EQ(splitByWeight({nan, 2.0}, 9), (std::vector<uint64_t>{0, 9}));
  EXPECT_EQ(splitByWeight({inf, nan}, 9), (std::vector<uint64_t>{0, 0}));
  // Finite weights whose sum overflows double are not a case float lights can make.
  EXPECT_EQ(splitByWeight({1e300, 1e300}, 4), (std::vector<uint64_t>{2, 2}));
}

// A line through a glass ball records glass-only shadows behind it; a line through
// an opaque ball records opaque shadows, also behind glass crossed later.
}  // namespace
}  // namespace penumbra
