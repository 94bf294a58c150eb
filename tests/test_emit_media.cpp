// Photons through participating media: the power tally balances, an absorbing sphere
// lets exp(-sigma_a R) escape, the volume map's stored power in an infinite medium
// matches the random walk's energy and spread, and the photons do not depend on threads.
#include "core/media/phase_function.h"
#include "emit/emit_physical.h"
#include "support/emit_box.h"
#include <gtest/gtest.h>
#include <tbb/global_control.h>
#include <cmath>
#include <cstring>

namespace penumbra {
namespace {

using testing::pointLight;

Medium fog(float sigmaA, float sigmaS, float g) {
  Medium m;
  m.name = "fog";
  m.sigmaA = Color(sigmaA);
  m.sigmaS = Color(sigmaS);
  m.g = g;
  return m;
}

// A point light at the centre of a sphere of radius 1 filled with `m`; its surface
// is glass of index `ior` (1: an invisible interface that every photon crosses).
Scene sphereOfMedium(const Medium& m, float ior) {
  Scene scene;
  Material glass;
  glass.name = "glass";
  glass.transparent = true;
  glass.ior = ior;
  scene.materials.push_back(glass);
  Sphere s;
  s.radius = 1.0f;
  s.media = {0, kNoMedium, true};
  scene.spheres.push_back(s);
  scene.media.push_back(m);
  scene.lights.push_back(pointLight(Vec3(0.0f)));
  scene.lights.back().medium = 0;
  scene.render.seed = 777;
  return scene;
}

// A point light in a medium filling the scene: one far, tiny black sphere keeps the
// tracer's scene non-empty and catches nothing that matters.
Scene infiniteMedium(const Medium& m) {
  Scene scene;
  Material black;
  black.name = "black";
  black.diffuse = Color(0.0f);
  scene.materials.push_back(black);
  Sphere far;
  far.center = Vec3(1e4f, 0.0f, 0.0f);
  far.radius = 1e-3f;
  scene.spheres.push_back(far);
  scene.media.push_back(m);
  scene.sceneMedium = 0;
  scene.lights.push_back(pointLight(Vec3(0.0f)));
  scene.lights.back().medium = 0;
  scene.render.seed = 4242;
  return scene;
}

EmitOptions volumeOnly(uint64_t n) {
  EmitOptions o;
  o.maps = PerMap<bool>{};
  o.maps[MapKind::Volume] = true;
  o.budgets[MapKind::Volume] = n;
  return o;
}

void expectBalanced(const PhotonTally& t) {
  const glm::dvec3 rest = t.emitted - t.absorbed - t.escaped - t.capped;
  for (int c = 0; c < 3; ++c) EXPECT_LT(std::abs(rest[c]), 1e-3 * t.emitted[c]) << "channel " << c;
}

TEST(EmitMedia, AbsorbingSphereLetsExpOfMinusSigmaREscape) {
  const float sigmaA = 0.7f;
  Scene scene = sphereOfMedium(fog(sigmaA, 0.0f, 0.0f), 1.0f);
  TraceScene tracer(scene);
  const EmittedPhotons e = emitPhysicalPhotons(scene, tracer, 0, volumeOnly(100000));
  const PhotonTally& t = e.tally[MapKind::Volume];
  expectBalanced(t);
  // Every photon carries the same power: the escaped share is binomial, sd ~0.3%.
  EXPECT_NEAR(t.escaped.x / t.emitted.x, std::exp(-sigmaA), 0.01 * std::exp(-sigmaA));
  EXPECT_TRUE(e.batches.get<MapKind::Volume>().empty());  // nothing scatters
}

TEST(EmitMedia, ScatteringGlassSphereAndSceneMediumBalance) {
  Scene glass = sphereOfMedium(fog(0.2f, 0.9f, 0.5f), 1.33f);
  TraceScene glassTracer(glass);
  EmitOptions o = volumeOnly(50000);
  o.maps[MapKind::Global] = true;
  o.budgets[MapKind::Global] = 50000;
  const EmittedPhotons a = emitPhysicalPhotons(glass, glassTracer, 0, o);
  expectBalanced(a.tally[MapKind::Volume]);
  expectBalanced(a.tally[MapKind::Global]);
  EXPECT_GT(a.tally[MapKind::Volume].escaped.x, 0.0);
  EXPECT_GT(a.batches.get<MapKind::Volume>().size(), 0u);

  Scene open = infiniteMedium(fog(0.3f, 0.7f, -0.3f));
  TraceScene openTracer(open);
  const EmittedPhotons b = emitPhysicalPhotons(open, openTracer, 0, volumeOnly(50000));
  const PhotonTally& t = b.tally[MapKind::Volume];
  expectBalanced(t);
  EXPECT_EQ(t.escaped.x, 0.0);  // an infinite medium lets nothing out
  // Capped after max_bounces + 1 scatters: albedo^17 of the power (~115 photons).
  const double capped = std::pow(0.7, open.photons.maxBounces + 1);
  EXPECT_NEAR(t.capped.x / t.emitted.x, capped, 0.3 * capped);
}

// In an infinite grey medium of albedo a every photon collides; its n-th collision
// scatters with probability a^n and is stored for n >= 2 (an event came before), at
// x_n after n exponential flights (mean mu) with HG-correlated directions:
// E|x_n|^2 = mu^2 (2n + 2 sum_{d=1}^{n-1} (n - d) g^d). So the stored power is
// Phi sum_{n>=2} a^n and its r^2 moment Phi sum_{n>=2} a^n E|x_n|^2: the stored
// density is sigma_s x the (collided) fluence, weighed over all space twice.
TEST(EmitMedia, InfiniteMediumStoresTheRandomWalksPowerAndSpread) {
  for (float g : {0.0f, 0.6f}) {
    const float sigmaA = 0.5f, sigmaS = 0.5f, a = sigmaS / (sigmaA + sigmaS), mu = 1.0f / (sigmaA + sigmaS);
    Scene scene = infiniteMedium(fog(sigmaA, sigmaS, g));
    scene.photons.maxBounces = 60;
    TraceScene tracer(scene);
    const uint64_t n = 200000;
    const EmittedPhotons e = emitPhysicalPhotons(scene, tracer, 0, volumeOnly(n));
    double power = 0.0, moment = 0.0;
    for (const VolumePhoton& p : e.batches.get<MapKind::Volume>()) {
      const double w = p.power.color().r;
      power += w;
      moment += w * glm::dot(p.position, p.position);
      ASSERT_EQ(p.medium, 0);
    }
    const double phi = e.tally[MapKind::Volume].emitted.x;
    double wantPower = 0.0, wantMoment = 0.0;
    for (int k = 2; k <= 61; ++k) {
      double spread = 2.0 * k;
      for (int d = 1; d < k; ++d) spread += 2.0 * (k - d) * std::pow(double(g), d);
      wantPower += std::pow(a, k);
      wantMoment += std::pow(a, k) * spread * mu * mu;
    }
    EXPECT_NEAR(power / phi, wantPower, 0.025 * wantPower) << "g " << g;
    EXPECT_NEAR(moment / phi, wantMoment, 0.05 * wantMoment) << "g " << g;
    EXPECT_NEAR(e.tally[MapKind::Volume].stored[MapKind::Volume].x, power, 1e-2 * power);
  }
}

TEST(EmitMedia, VolumePhotonsIdenticalForOneAndTwoThreads) {
  Scene scene = sphereOfMedium(fog(0.1f, 1.5f, 0.3f), 1.5f);
  TraceScene tracer(scene);
  auto run = [&](int threads) {
    tbb::global_control c(tbb::global_control::max_allowed_parallelism, threads);
    return emitPhysicalPhotons(scene, tracer, 3, volumeOnly(30000)).batches.get<MapKind::Volume>().flatten();
  };
  const auto one = run(1), two = run(2);
  ASSERT_EQ(one.size(), two.size());
  ASSERT_GT(one.size(), 1000u);
  EXPECT_EQ(std::memcmp(one.data(), two.data(), one.size() * sizeof(VolumePhoton)), 0);
}

TEST(EmitMedia, CausticPassEndsAtAMediumScatter) {
  // Fog so thick that every photon scatters before it reaches the glass: no L S+ D path.
  Scene scene = infiniteMedium(fog(0.0f, 50.0f, 0.0f));
  Material glass;
  glass.transparent = true;
  scene.materials.push_back(glass);
  Sphere ball;
  ball.center = Vec3(0.0f, 0.0f, 3.0f);
  ball.radius = 1.0f;
  ball.material = 1;
  ball.media = {0, 0, true};
  scene.spheres.push_back(ball);
  TraceScene tracer(scene);
  EmitOptions o;
  o.maps = PerMap<bool>{};
  o.maps[MapKind::Caustic] = true;
  o.budgets[MapKind::Caustic] = 20000;
  const EmittedPhotons e = emitPhysicalPhotons(scene, tracer, 0, o);
  EXPECT_TRUE(e.batches.get<MapKind::Caustic>().empty());
  expectBalanced(e.tally[MapKind::Caustic]);
}

TEST(EmitMedia, NoMediumNoVolumePhotons) {
  Scene scene = testing::boxScene(1.0f, Vec3(0.1f), 0);
  scene.materials[0].diffuse = Color(0.5f);
  TraceScene tracer(scene);
  EmitOptions o = volumeOnly(10000);
  const EmittedPhotons e = emitPhysicalPhotons(scene, tracer, 0, o);
  EXPECT_EQ(e.emitted[MapKind::Volume], 0u);
  EXPECT_TRUE(e.batches.get<MapKind::Volume>().empty());
  EXPECT_EQ(budgetsOf(scene)[MapKind::Volume], 0u);
}

}  // namespace
}  // namespace penumbra
