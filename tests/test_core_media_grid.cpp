// Density grids tracked against their majorant equal the closed forms: a constant grid
// is the homogeneous medium (ratio-tracked transmittance, delta-tracked collision
// distances and RGB weights), a linear ramp follows exp(-integral), a ray through the
// whole grid sees its trilinear edges, a sparse blob matches quadrature, and extreme or
// empty grids stay finite. Every grid has a rotated, scaled, translated worldToGrid;
// every case runs with the global majorant alone and with per-block majorants.
#include "core/media/density_grid.h"
#include "support/media_tracking.h"
#include <glm/gtc/matrix_transform.hpp>
#include <gtest/gtest.h>
#include <functional>
#include <memory>
#include <string>

namespace penumbra {
namespace {

using testing::collisionChi2;
using testing::collisions;
using testing::makeMedium;
using testing::Mean;

constexpr int kN = 20;                         // voxels per axis: 3 majorant blocks
const Vec3 kLatticeOrigin(1.0f, -2.0f, 0.5f);  // voxel (0, 0, 0)'s centre in the world
const Vec3 kVoxel(0.1f, 0.2f, 0.08f);          // anisotropic voxel size
constexpr int kCases = 3 * 2;                  // chi-squared cases in this file
const double kLevel = chi2::sidakLevel(0.01, kCases);

// Lattice -> world: scale, then a 30 degree turn, then the origin.
glm::mat4 gridToWorld() {
  const glm::mat4 turn = glm::rotate(glm::mat4(1.0f), glm::radians(30.0f), glm::normalize(Vec3(1.0f, 2.0f, 0.5f)));
  return glm::translate(glm::mat4(1.0f), kLatticeOrigin) * turn * glm::scale(glm::mat4(1.0f), kVoxel);
}
Vec3 world(const Vec3& lattice) { return Vec3(gridToWorld() * glm::vec4(lattice, 1.0f)); }
Vec3 worldDir(const Vec3& lattice) { return Vec3(gridToWorld() * glm::vec4(lattice, 0.0f)); }

// A grid of kN^3 voxels holding density(i, j, k); majorant 0: the largest value.
std::shared_ptr<DensityGrid> makeGrid(const std::function<float(int, int, int)>& density, bool blocks,
                                      float majorant = 0.0f) {
  auto g = std::make_shared<DensityGrid>();
  g->nx = g->ny = g->nz = kN;
  g->values.resize(size_t(kN) * kN * kN);
  for (int k = 0; k < kN; ++k)
    for (int j = 0; j < kN; ++j)
      for (int i = 0; i < kN; ++i) {
        const float v = density(i, j, k);
        g->values[(size_t(k) * kN + j) * kN + i] = v;
        g->maxDensity = std::max(g->maxDensity, v);
      }
  if (majorant > 0.0f) g->maxDensity = majorant;
  g->worldToGrid = glm::inverse(gridToWorld());
  // The world box around the trilinear support, which reaches one voxel past the centres.
  g->worldLo = Vec3(kInf), g->worldHi = Vec3(-kInf);
  for (int c = 0; c < 8; ++c) {
    const Vec3 corner = world(Vec3(c & 1 ? kN : -1, c & 2 ? kN : -1, c & 4 ? kN : -1));
    g->worldLo = glm::min(g->worldLo, corner), g->worldHi = glm::max(g->worldHi, corner);
  }
  if (blocks) g->majorants = buildMajorantGrid(*g);
  return g;
}

Medium gridMedium(const Color& sigmaA, const Color& sigmaS, std::shared_ptr<DensityGrid> g) {
  Medium m = makeMedium(sigmaA, sigmaS);
  m.density = std::move(g);
  return m;
}

// A segment between two lattice points inside the centres' hull (no edge ramp), the ray
// starting 0.3 before it.
struct Segment {
  Vec3 o, d;
  float a, b;
};
Segment interiorSegment() {
  const Vec3 p0 = world(Vec3(0.5f, 1.0f, 0.5f)), p1 = world(Vec3(17.5f, 16.0f, 18.2f));
  const Vec3 d = glm::normalize(p1 - p0);
  const float len = glm::length(p1 - p0);
  return {p0 - 0.3f * d, d, 0.3f, 0.3f + len};
}

Mean ratioTracked(const Medium& m, const Segment& s, int channel, int n, uint64_t seed) {
  Mean t;
  Rng rng(seed);
  for (int k = 0; k < n; ++k) t.add(mediumTransmittance(m, s.o, s.d, s.a, s.b, rng)[channel]);
  return t;
}

// The parameter: build per-block majorants (true) or track at the global maximum.
class DensityGridTracking : public ::testing::TestWithParam<bool> {};

void expectChi2(const chi2::Result& r, const std::string& name) {
  EXPECT_TRUE(r.failure.empty()) << name << ": " << r.failure;
  EXPECT_GE(r.pValue, kLevel) << name << ": chi2 " << r.statistic << " on " << r.dof << " dof;" << r.worst;
}

TEST_P(DensityGridTracking, ConstantGridEqualsTheHomogeneousMedium) {
  const float rho = 0.8f;
  const Color sa(0.1f, 0.05f, 0.15f), ss(0.3f, 0.45f, 0.6f);
  const Segment s = interiorSegment();
  const double d = double(s.b) - s.a;
  const Color st = rho * (sa + ss);  // the homogeneous equivalent: 0.32, 0.4, 0.6
  // The tight majorant (the grid's maximum) and a loose one (1.25 x): both unbiased.
  uint64_t seed = GetParam() ? 41 : 141;
  for (float majorant : {0.0f, 1.0f}) {
    const std::string name = majorant > 0.0f ? "loose majorant" : "tight majorant";
    const Medium m = gridMedium(sa, ss, makeGrid([&](int, int, int) { return rho; }, GetParam(), majorant));
    for (int c = 0; c < 3; ++c) {
      const Mean t = ratioTracked(m, s, c, 40000, seed++);
      EXPECT_NEAR(t.mean(), std::exp(-double(st[c]) * d), 5.0 * t.stdError() + 1e-6) << name << " channel " << c;
    }
    const auto stats = collisions(m, s.o, s.d, s.a, s.b, 200000, seed++, 30, float(d));
    ASSERT_TRUE(stats.finite) << name;
    const auto mixture = [&](double x) { return testing::heroMixtureCdf(st, x); };
    expectChi2(collisionChi2(stats, mixture, float(d), 1.0 - mixture(d)), name);
    for (int c = 0; c < 3; ++c) {
      const double tr = std::exp(-double(st[c]) * d), scattered = double(ss[c]) / (sa + ss)[c] * (1.0 - tr);
      EXPECT_NEAR(stats.weightNone[c].mean(), tr, 5.0 * stats.weightNone[c].stdError() + 1e-6) << name << c;
      EXPECT_NEAR(stats.weightHit[c].mean(), scattered, 5.0 * stats.weightHit[c].stdError() + 1e-6) << name << c;
    }
  }
}

TEST_P(DensityGridTracking, LinearRampFollowsTheIntegralOfItsDensity) {
  // Density 0.1 + 0.1 i: trilinear makes it linear along any interior segment, so the
  // optical depth to x is sigmaT (rho0 x + (rho1 - rho0) x^2 / 2d). A grey medium.
  const Medium m =
      gridMedium(Color(0.1f), Color(0.4f), makeGrid([](int i, int, int) { return 0.1f + 0.1f * i; }, GetParam()));
  const Segment s = interiorSegment();
  const double d = double(s.b) - s.a, sigmaT = 0.5, rho0 = 0.1 + 0.1 * 0.5, rho1 = 0.1 + 0.1 * 17.5;
  const auto depth = [&](double x) { return sigmaT * (rho0 * x + (rho1 - rho0) * x * x / (2.0 * d)); };
  const Mean t = ratioTracked(m, s, 1, 40000, 51);
  EXPECT_NEAR(t.mean(), std::exp(-depth(d)), 5.0 * t.stdError() + 1e-6);
  const auto stats = collisions(m, s.o, s.d, s.a, s.b, 200000, 53, 30, float(d));
  ASSERT_TRUE(stats.finite);
  expectChi2(collisionChi2(stats, [&](double x) { return 1.0 - std::exp(-depth(x)); }, float(d), std::exp(-depth(d))),
             "ramp");
  // Grey: the weights are exact, the albedo on a collision and 1 without.
  Rng rng(3);
  for (int k = 0; k < 1000; ++k) {
    const MediumCollision c = sampleCollision(m, s.o, s.d, s.a, s.b, rng);
    EXPECT_NEAR(c.weight.r, c.collided ? 0.8f : 1.0f, 1e-6f);
  }
}

TEST_P(DensityGridTracking, AnInfiniteRaySeesTheWholeGridAndItsEdges) {
  // Along the lattice's x through voxel centres (y, z interior): the trilinear density
  // ramps from 0 to rho over the voxel past each end, so the depth is rho x kN voxels x
  // the voxel's length x sigmaT.
  const float rho = 0.6f;
  const Medium m = gridMedium(Color(0.5f, 0.0f, 1.0f), Color(0.5f, 1.0f, 0.0f),
                              makeGrid([&](int, int, int) { return rho; }, GetParam()));
  const Vec3 start = world(Vec3(-5.0f, 3.0f, 4.0f)), x = glm::normalize(worldDir(Vec3(1.0f, 0.0f, 0.0f)));
  const double depth = double(rho) * kN * kVoxel.x;  // per unit sigmaT (1 in every channel)
  Rng rng(61);
  Mean t;
  for (int k = 0; k < 40000; ++k) t.add(mediumTransmittance(m, start, x, 0.0f, kInf, rng).g);
  EXPECT_NEAR(t.mean(), std::exp(-depth), 5.0 * t.stdError() + 1e-6);
  const auto stats = collisions(m, start, x, 0.0f, kInf, 100000, 67, 10, 10.0f);
  ASSERT_TRUE(stats.finite);  // a flight without a collision ends at b = inf, not the box
  for (int c = 0; c < 3; ++c) {
    EXPECT_NEAR(stats.weightNone[c].mean(), std::exp(-depth), 5.0 * stats.weightNone[c].stdError() + 1e-6) << c;
  }
  // Starting at the box's far side and leaving: nothing on the way.
  Rng rng2(1);
  EXPECT_EQ(mediumTransmittance(m, world(Vec3(kN + 1.0f, 3.0f, 4.0f)), x, 0.0f, kInf, rng2), Color(1.0f));
}

TEST_P(DensityGridTracking, AClearChannelPassesAndTheOthersKeepTheirOwnWeights) {
  // sigmaT (0, 0.5, 2) in a ramp: the red channel never meets anything (mean weight 1
  // without a collision, 0 with one) while green and blue follow their own depths.
  const Color sa(0.0f, 0.25f, 0.5f), ss(0.0f, 0.25f, 1.5f);
  const Medium m = gridMedium(sa, ss, makeGrid([](int i, int, int) { return 0.1f + 0.05f * i; }, GetParam()));
  const Segment s = interiorSegment();
  const double d = double(s.b) - s.a, rho = 0.1 + 0.05 * 0.5 + 0.5 * 0.05 * 17.0;  // the mean density
  const auto stats = collisions(m, s.o, s.d, s.a, s.b, 200000, 91, 10, float(d));
  ASSERT_TRUE(stats.finite);
  EXPECT_NEAR(stats.weightNone[0].mean(), 1.0, 5.0 * stats.weightNone[0].stdError() + 1e-6);
  EXPECT_EQ(stats.weightHit[0].mean(), 0.0);
  for (int c = 1; c < 3; ++c) {
    const double st = (sa + ss)[c], tr = std::exp(-st * rho * d);
    EXPECT_NEAR(stats.weightNone[c].mean(), tr, 5.0 * stats.weightNone[c].stdError() + 1e-6) << c;
    EXPECT_NEAR(stats.weightHit[c].mean(), ss[c] / st * (1.0 - tr), 5.0 * stats.weightHit[c].stdError() + 1e-6) << c;
  }
  EXPECT_LE(stats.maxWeight, 3.0 + 1e-5);  // the balance heuristic's bound, albedo <= 1
}

TEST_P(DensityGridTracking, ASparseBlobMatchesQuadratureOfItsDensity) {
  // Density 3 in two 3^3 blobs of voxels, 0 elsewhere: most of the ray crosses empty
  // blocks (the case per-block majorants are for). The blobs sit just inside majorant
  // blocks next to empty ones, so a walk that misplaces a block boundary misses density.
  // Reference: the midpoint rule on at() along the ray, fine enough for its pieces.
  const auto inBlob = [](int i, int lo) { return i >= lo && i <= lo + 2; };
  const Medium m = gridMedium(Color(0.1f), Color(0.4f), makeGrid([&](int i, int j, int k) {
    const bool first = inBlob(i, 12) && inBlob(j, 12) && inBlob(k, 12);
    return first || (inBlob(i, 16) && inBlob(j, 16) && inBlob(k, 16)) ? 3.0f : 0.0f;
  }, GetParam()));
  const Vec3 p0 = world(Vec3(-2.0f, -1.0f, -3.0f)), p1 = world(Vec3(21.0f, 22.0f, 21.5f));
  const Vec3 d = glm::normalize(p1 - p0);
  const float len = glm::length(p1 - p0);
  double integral = 0.0;
  const int steps = 200000;
  for (int i = 0; i < steps; ++i) integral += m.density->at(p0 + (i + 0.5f) * (len / steps) * d) * double(len) / steps;
  ASSERT_GT(integral, 0.5);
  const double tr = std::exp(-0.5 * integral);
  Mean t;
  Rng rng(81);
  for (int k = 0; k < 40000; ++k) t.add(mediumTransmittance(m, p0, d, 0.0f, len, rng).b);
  EXPECT_NEAR(t.mean(), tr, 5.0 * t.stdError() + 1e-6);
  const auto stats = collisions(m, p0, d, 0.0f, len, 100000, 83, 10, len);
  ASSERT_TRUE(stats.finite);
  EXPECT_NEAR(stats.weightNone[0].mean(), tr, 5.0 * stats.weightNone[0].stdError() + 1e-6);
  EXPECT_NEAR(stats.weightHit[0].mean(), 0.8 * (1.0 - tr), 5.0 * stats.weightHit[0].stdError() + 1e-6);
}

TEST_P(DensityGridTracking, ExtremeAndEmptyGridsStayFinite) {
  const Segment s = interiorSegment();
  Rng rng(71);
  // Density scaled to sigma ~ 1e30: opaque, every weight finite, and the call returns
  // (the step limit) even where the trilinear edge makes the density tiny.
  const Medium wall = gridMedium(Color(0.5e30f), Color(0.5e30f), makeGrid([](int, int, int) { return 1.0f; }, GetParam()));
  const Vec3 x = glm::normalize(worldDir(Vec3(1.0f, 0.0f, 0.0f)));
  for (const Vec3& o : {s.o, world(Vec3(-3.0f, 3.0f, 3.0f))}) {
    const Vec3 d = o == s.o ? s.d : x;
    const Color t = mediumTransmittance(wall, o, d, 0.0f, kInf, rng);
    EXPECT_TRUE(isFinite(t) && t.r < 1e-6f) << t.r;
    const MediumCollision c = sampleCollision(wall, o, d, 0.0f, kInf, rng);
    EXPECT_TRUE(c.collided && isFinite(c.weight) && std::isfinite(c.t));
  }
  // An all-zero grid, a zero majorant, a ray that misses the box (one direction
  // component 0), and an empty segment: vacuum.
  const Medium empty = gridMedium(Color(1.0f), Color(1.0f), makeGrid([](int, int, int) { return 0.0f; }, GetParam()));
  const Medium full = gridMedium(Color(1.0f), Color(1.0f), makeGrid([](int, int, int) { return 1.0f; }, GetParam()));
  const Vec3 above = world(Vec3(3.0f, float(kN) + 2.0f, 3.0f));
  const struct {
    const Medium* m;
    Vec3 o, d;
    float a, b;
  } cases[] = {{&empty, s.o, s.d, s.a, s.b},
               {&full, above, x, 0.0f, kInf},
               {&full, s.o, s.d, 1.0f, 1.0f}};
  // The majorant the cost model prices: sigmaT's largest channel x the largest density.
  EXPECT_FLOAT_EQ(mediumMajorant(full), 2.0f);
  EXPECT_FLOAT_EQ(mediumMajorant(empty), 0.0f);
  EXPECT_FLOAT_EQ(mediumMajorant(makeMedium(Color(0.1f, 0.2f, 0.3f), Color(1.0f, 0.5f, 0.0f))), 1.1f);
  for (const auto& c : cases) {
    EXPECT_EQ(mediumTransmittance(*c.m, c.o, c.d, c.a, c.b, rng), Color(1.0f));
    const MediumCollision col = sampleCollision(*c.m, c.o, c.d, c.a, c.b, rng);
    EXPECT_FALSE(col.collided);
    EXPECT_EQ(col.weight, Color(1.0f));
    EXPECT_EQ(col.t, c.b);
  }
}

INSTANTIATE_TEST_SUITE_P(Majorants, DensityGridTracking, ::testing::Bool(),
                         [](const ::testing::TestParamInfo<bool>& p) { return p.param ? "blocks" : "global"; });

}  // namespace
}  // namespace penumbra
