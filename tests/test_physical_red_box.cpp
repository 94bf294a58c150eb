// The red box: energy balance fixes the area-mean indirect radiance per channel,
// and the stored power per channel follows the truncated geometric series in
// max_bounces, for the physical model and for the classic roulette alike.
#include "support/physical_fixtures.h"
#include "support/emit_fixtures.h"

namespace penumbra {
namespace {

// ---------------------------------------------------------------------------
// c. The red box.

const Vec3 kBoxMin(-1.0f, 0.0f, -0.6f), kBoxMax(1.0f, 1.5f, 0.6f);
const Color kRed(0.9f, 0.05f, 0.05f);
const Vec3 kBoxLight(0.3f, 1.0f, -0.1f);

Scene redBox(ShadingModel model, int maxBounces) {
  Scene scene = physicalScene();
  scene.render.model = model;
  Material m = lambert("red", kRed);
  m.pR = 0.5f;  // the report's roulette (classic model only)
  scene.materials.push_back(m);
  scene.meshes.push_back(makeBox(kBoxMin, kBoxMax, 0));
  scene.lights.push_back(point(kBoxLight, Color(1.0f), 1.5f));
  scene.photons.maxBounces = maxBounces;
  return scene;
}

double boxArea() {
  Vec3 e = kBoxMax - kBoxMin;
  return 2.0 * (double(e.x) * e.y + double(e.y) * e.z + double(e.x) * e.z);
}

// A point uniformly distributed by area over the box's surface.
Vec3 uniformOnBox(Rng& rng) {
  const Vec3 e = kBoxMax - kBoxMin;
  const double faces[3] = {double(e.y) * e.z, double(e.x) * e.z, double(e.x) * e.y};  // normal x, y, z
  double pick = rng.uniform() * (faces[0] + faces[1] + faces[2]);
  int axis = pick < faces[0] ? 0 : (pick < faces[0] + faces[1] ? 1 : 2);
  Vec3 p = kBoxMin + Vec3(rng.uniform(), rng.uniform(), rng.uniform()) * e;
  p[axis] = rng.uniform() < 0.5f ? kBoxMin[axis] : kBoxMax[axis];
  return p;
}

// Expected stored power per channel: a photon's power after k bounces keeps
// rho / q per channel with survival q = max(rho) (physical), so the expected power
// stored at hit k is Phi rho^k, and hits 1..M are stored: Phi rho (1 - rho^M) / (1 - rho).
glm::dvec3 expectedStoredPhysical(int maxBounces) {
  const glm::dvec3 phi = glm::dvec3(4.0 * kPiD * 1.5);
  glm::dvec3 out;
  for (int c = 0; c < 3; ++c) {
    double r = kRed[c];
    out[c] = phi[c] * r * (1.0 - std::pow(r, maxBounces)) / (1.0 - r);
  }
  return out;
}

TEST(RedBox, PhysicalAreaMeanIndirectRadianceMatchesEnergyBalance) {
  // Closed box 2 x 1.5 x 1.2, rho = (0.9, 0.05, 0.05) everywhere, point light of
  // I = 1.5 W/sr inside. Energy balance: the power reaching the walls after >= 1
  // bounce is Phi rho / (1 - rho) per channel (Phi = 4 pi I), so the area mean of
  // the indirect exitance is that / A and of the radiance rho/pi (Phi/A) rho/(1-rho)
  // (times 1 - rho^64 for the bounce cap: 0.12% for red).
  Scene scene = redBox(ShadingModel::Physical, 64);
  scene.photons.globalPhotons = 200000;
  Rig rig(scene);
  EmittedPhotons photons = emitPhysicalPhotons(scene, rig.tracer, 0, sceneEmit(scene));
  const glm::dvec3 stored = expectedStoredPhysical(64);
  const PhotonTally& t = photons.tally[MapKind::Global];
  for (int c = 0; c < 3; ++c) {
    // Red: stored power per photon ~ geometric(0.9), rel. s.e. 1.05/sqrt(N) = 0.24%;
    // green/blue are dominated by the first bounce (s.e. ~0.1%). Tolerance 1%.
    EXPECT_LT(rel(t.stored[MapKind::Global][c], stored[c]), 0.01) << "channel " << c;
    EXPECT_EQ(t.escaped[c], 0.0);
    EXPECT_NEAR(t.absorbed[c] + t.capped[c], t.emitted[c], 1e-9 * t.emitted[c]);
  }

  // The map stores each photon's power as shared-exponent RGB: every channel within
  // 2^-8 of the photon's largest (red here), rounded to nearest. Red's sum therefore
  // stays within 2^-8 of the tally. Green/blue keep only that absolute precision, and
  // the rounding does not average out: all photons of one bounce depth carry the
  // same colour, so they round alike. Second-bounce green is 0.0556^2 x red = 0.61
  // mantissa units and stores as 1 (+64%); it is ~5% of the green total, so the map's
  // green is ~3% above the tally (measured +2.95%; 1e-5 of the red radiance, invisible,
  // but beyond this test's 2% per channel against the energy balance). Hence the
  // map against the tally at the format's bound, and the gather below against what
  // the map holds, at its old 2%.
  glm::dvec3 inMap(0.0), bound(0.0);
  for (const IndirectPhoton& p : photons.batches.get<MapKind::Global>()) {
    const Color c = p.power.color();
    inMap += glm::dvec3(c);
    bound += glm::dvec3(0x1p-8 * maxComponent(c) / (1.0 - 0x1p-8));  // 2^-8 of the float's largest
  }
  for (int c = 0; c < 3; ++c) {
    EXPECT_LE(std::abs(inMap[c] - t.stored[MapKind::Global][c]), bound[c]) << "channel " << c;
  }
  std::printf("[ info ] map / tally - 1 per channel: %+.4f %+.4f %+.4f\n", inMap.r / t.stored[MapKind::Global].r - 1.0,
              inMap.g / t.stored[MapKind::Global].g - 1.0, inMap.b / t.stored[MapKind::Global].b - 1.0);

  IndirectPhotonMap map;
  map.build(std::move(photons.batches.get<MapKind::Global>()));
  rig.ctx.maps.get<MapKind::Global>() = &map;
  // A fixed gather radius r (a progressive pass of photons.radius): every photon
  // within r on the same face counts, unbiased away from edges. Within r of an edge
  // the disc reaches past its face; the adjacent face's photons mark the edge and the
  // estimate divides by the kernel's mass on the face's side, so no edge loss remains
  // (without that, the area mean would be low by 8 r / (15 pi) per unit of perimeter
  // over the area: 0.44% here).
  const float r = 0.01f;
  rig.ctx.gathers[MapKind::Global].k = 0;
  rig.ctx.gathers[MapKind::Global].maxRadius = r;
  const Vec3 inside(0.05f, 0.7f, 0.05f);  // the box is convex: it sees every wall point
  const int points = 20000;
  Rng rng(9);
  glm::dvec3 sum(0.0);
  for (int i = 0; i < points; ++i) {
    Vec3 p = uniformOnBox(rng);
    sum += glm::dvec3(trace(rig, makeRay(inside, p - inside), kTermGlobal));
  }
  const glm::dvec3 mean = sum / double(points);
  for (int c = 0; c < 3; ++c) {
    const double want = kRed[c] / kPiD * inMap[c] / boxArea();
    // ~39 photons per disc: ~19% scatter per point, 0.15% over 20000 points (the
    // photon total's 0.24% is checked above, against the tally). Tolerance 2% per
    // channel as asked.
    EXPECT_LT(rel(mean[c], want), 0.02) << "channel " << c << ": " << mean[c] << " vs " << want;
  }
}

TEST(RedBox, PhysicalStoredPowerFollowsTheBounceCap) {
  // Red survives each bounce with q = 0.9 keeping its power, so the cap M truncates
  // the series: stored = Phi 0.9 (1 - 0.9^M) / 0.1 -- 81.5% of the limit at M = 16,
  // 96.6% at 32, 99.9% at 64, and 64 -> 128 adds < 0.2%. (Unlike the classic p_r = 0.5
  // roulette, 16 and 64 must NOT agree here: the cap costs 0.9^16 = 18.5% of red.)
  // Tolerance 1% on each (rel. s.e. <= 0.24% at 200k photons).
  double last = 0.0;
  for (int m : {16, 32, 64, 128}) {
    Scene scene = redBox(ShadingModel::Physical, m);
    scene.photons.globalPhotons = 200000;
    TraceScene tracer(scene);
    EmittedPhotons photons = emitPhysicalPhotons(scene, tracer, 0, sceneEmit(scene));
    const glm::dvec3 want = expectedStoredPhysical(m);
    for (int c = 0; c < 3; ++c) {
      EXPECT_LT(rel(photons.tally[MapKind::Global].stored[MapKind::Global][c], want[c]), 0.01) << "M=" << m << " ch " << c;
    }
    double red = photons.tally[MapKind::Global].stored[MapKind::Global].r;
    if (m == 128) {
      EXPECT_LT(rel(red, last), 0.01) << "not converged from 64 to 128";
    }
    last = red;
  }
}

TEST(RedBox, ClassicRouletteStoredPowerConvergesWithMaxBounces) {
  // The report's roulette: survive with p_r = 0.5, a survivor takes colour / max(colour)
  // (red keeps its power, green and blue keep 0.05/0.9), times 2 cos for the uniform
  // bounce (mean 1). The density estimator stores every hit after the first, so the
  // expected stored power is Phi sum_{k=1..M} (p_r c)^k with c = colour / max:
  // red Phi (1 - 0.5^M) = Phi, green/blue Phi x 0.0278 / (1 - 0.0278). It must
  // converge: 32 -> 64 changes it by < 1%. (With the old colour / mean rule red
  // gained 0.5 x 0.9 / 0.333 = 1.35 per bounce and grew without bound.)
  // Tolerance 2% per channel (red's rel. s.e. is sqrt(5 / N) = 0.5% at N = 200k).
  const double phi = 4.0 * kPiD * 1.5;
  const glm::dvec3 c = glm::dvec3(kRed) / double(maxComponent(kRed));
  for (HemisphereSampling sampling : {HemisphereSampling::Uniform, HemisphereSampling::Cosine}) {
    glm::dvec3 total[3];
    int i = 0;
    for (int m : {16, 32, 64}) {
      Scene scene = redBox(ShadingModel::Classic, m);
      scene.photons.indirectPhotons = 200000;
      scene.photons.estimator = IndirectEstimator::Density;
      scene.photons.sampling = sampling;
      TraceScene tracer(scene);
      EmitOptions options;
      options.maps[MapKind::Shadow] = false;
      EmittedPhotons maps = emitPhotons(scene, tracer, sceneEmit(scene, options));
      glm::dvec3 sum(0.0);
      for (const IndirectPhoton& p : maps.batches.get<MapKind::Indirect>()) sum += glm::dvec3(p.power.color());
      total[i++] = sum;
      for (int ch = 0; ch < 3; ++ch) {
        const double x = 0.5 * c[ch];
        const double want = phi * x * (1.0 - std::pow(x, m)) / (1.0 - x);
        EXPECT_LT(rel(sum[ch], want), 0.02) << "M=" << m << " ch " << ch << ": " << sum[ch] << " vs " << want;
      }
    }
    for (int ch = 0; ch < 3; ++ch) {
      EXPECT_LT(rel(total[2][ch], total[1][ch]), 0.01) << "grew from 32 to 64, ch " << ch;
      EXPECT_LT(rel(total[1][ch], total[0][ch]), 0.01) << "grew from 16 to 32, ch " << ch;
    }
  }
}

}  // namespace
}  // namespace penumbra
