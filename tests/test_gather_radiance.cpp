// The physical radiance estimate's shrinking gathers across progressive passes, its
// order-independent Lambertian sum, and its kernel near a surface's edge: against the
// recurrence, Gamma's asymptote, brute force, the kernel's integral, and uniform
// photon grids that stop at a wall.
#include "gather/radiance_estimate.h"
#include "gather/surface_share.h"
#include "core/rng.h"
#include <gtest/gtest.h>
#include <cmath>
#include <cstdio>
#include <algorithm>
#include <functional>
#include <utility>
#include <vector>

namespace penumbra {
namespace {

TEST(PassSchedule, ShareFollowsTheRecurrenceAndItsAsymptote) {
  // r_{i+1}^2 = r_i^2 (i + alpha) / (i + 1) from K&Z's 1-based i, pass 0 at share 1.
  for (float alpha : {0.5f, 2.0f / 3.0f, 0.7f}) {
    double share = 1.0;
    for (uint32_t pass = 0; pass < 300; ++pass) {
      if (pass > 0) share *= (pass + double(alpha)) / (pass + 1.0);
      EXPECT_NEAR(passRadiusShare(pass, alpha) / share, 1.0, 1e-9) << alpha << " pass " << pass;
    }
    // share ~ i^(alpha - 1) / Gamma(1 + alpha) for large i (relative term O(1 / i)).
    const double i = 1e5, asymptote = std::pow(i, alpha - 1.0) / std::tgamma(1.0 + alpha);
    EXPECT_NEAR(passRadiusShare(uint32_t(i), alpha) / asymptote, 1.0, 1e-3) << alpha;
  }
  EXPECT_EQ(passRadiusShare(1000, 1.0f), 1.0);  // alpha 1: the radius stays
}

TEST(PassSchedule, KShrinksByTheShareRoundedAndStaysAboveTheMinimum) {
  const float alpha = 2.0f / 3.0f;
  EXPECT_EQ(passK(100, 0, alpha), 100);  // pass 0 is the one-pass estimate
  EXPECT_EQ(passK(100, 1, alpha), 83);   // 100 x (1 + 2/3) / 2
  EXPECT_EQ(passK(100, 63, alpha), static_cast<int>(std::lround(100 * passRadiusShare(63, alpha))));
  EXPECT_NEAR(passK(100, 63, alpha), 28, 0);  // share 0.2765
  EXPECT_EQ(passK(50, 100000, alpha), kMinPassK);
  EXPECT_EQ(passK(1, 10, alpha), 1);  // a k at or below the minimum stays
  int last = 1 << 30;
  for (uint32_t pass = 0; pass < 2000; ++pass) {
    const int k = passK(200, pass, alpha);
    EXPECT_LE(k, last);
    last = k;
  }
}

TEST(SurfaceShare, KernelMassBeyondAChordIsItsIntegral) {
  EXPECT_NEAR(kernelMassBeyond(0.0), 0.5, 1e-12);
  EXPECT_EQ(kernelMassBeyond(1.0), 0.0);
  EXPECT_EQ(kernelMassBeyond(3.0), 0.0);
  // Midpoint rule over the unit disc, K = 2 / pi (1 - rho^2).
  for (double d : {0.1, 0.3, 0.5, 0.8}) {
    const int n = 1000;
    double beyond = 0.0, all = 0.0;
    for (int i = 0; i < n; ++i) {
      for (int j = 0; j < n; ++j) {
        const double x = -1.0 + (i + 0.5) * 2.0 / n, y = -1.0 + (j + 0.5) * 2.0 / n;
        const double w = std::max(0.0, 1.0 - x * x - y * y);
        all += w;
        if (x > d) beyond += w;
      }
    }
    EXPECT_NEAR(kernelMassBeyond(d), beyond / all, 1e-4) << d;
  }
}

// Photons of power phi on a grid of spacing h, half a spacing in from every edge,
// over each face given: a point, two axes spanning the face, its extent along each,
// its normal. Every face's density is phi / h^2 (times `scale`).
constexpr float kH = 0.01f, kPhi = 0.002f;
struct Face {
  Vec3 corner, u, v;
  float lu, lv;
  Vec3 normal;
  float scale = 1.0f;
};

IndirectPhotonMap gridMap(const std::vector<Face>& faces) {
  PhotonArray<IndirectPhoton> photons;
  for (const Face& f : faces) {
    for (float a = 0.5f * kH; a < f.lu; a += kH) {
      for (float b = 0.5f * kH; b < f.lv; b += kH) {
        photons.push_back({f.corner + a * f.u + b * f.v, Color(kPhi * f.scale), encodeOctahedral(-f.normal),
                           encodeOctahedral(f.normal)});
      }
    }
  }
  IndirectPhotonMap map;
  map.build(std::move(photons));
  return map;
}

// The estimate over the expected irradiance / pi (a white Lambertian surface) at q.
double ratio(const IndirectPhotonMap& map, const Vec3& q, const Vec3& n, const PhotonGather& gather,
             double density = kPhi / (kH * kH)) {
  Bsdf white;
  white.type = BsdfType::Opaque;
  white.diffuse = Color(1.0f);
  GatherScratch scratch;
  const RadianceEstimate e = photonRadiance(map, white, BsdfFrame{n, n, true}, q, n, gather, scratch);
  return e.value.g / (density / kPi);
}

const Vec3 kX(1, 0, 0), kY(0, 1, 0), kZ(0, 0, 1);

// A Lambertian gather sums in fixed point, in whatever order the search returns the
// photons: the same bits whatever the search's hint ball, and the double-precision
// sum over the brute-force k nearest within float rounding. Powers span 2^-20..1, so
// the fixed point's scale (the map's brightest photon) is tested on dim photons too.
TEST(Radiance, ALambertianSumIsTheSameForAnySearchOrderAndMatchesBruteForce) {
  Rng rng(11);
  PhotonArray<IndirectPhoton> photons;
  for (int i = 0; i < 4000; ++i) {
    const Vec3 p(rng.uniform(), rng.uniform(), 0.0f);
    const float power = std::ldexp(0.5f + 0.5f * rng.uniform(), -static_cast<int>(rng.uniform() * 20.0f));
    photons.push_back({p, Color(power, 0.5f * power, 0.25f * power), encodeOctahedral(-kZ), encodeOctahedral(kZ)});
  }
  IndirectPhotonMap map;
  map.build(std::move(photons));
  Bsdf white;
  white.type = BsdfType::Opaque;
  white.diffuse = Color(0.8f);
  const int k = 60;
  for (int q = 0; q < 50; ++q) {
    const Vec3 at(0.2f + 0.6f * rng.uniform(), 0.2f + 0.6f * rng.uniform(), 0.0f);
    GatherScratch plain, hinted;
    plain.useHints = false;
    hinted.forcedHintRadius = 0.08f;  // a ball the search may have to grow: another order
    const BsdfFrame frame{kZ, kZ, true};
    const RadianceEstimate a = photonRadiance(map, white, frame, at, kZ, PhotonGather{k, 0.0f}, plain);
    const RadianceEstimate b = photonRadiance(map, white, frame, at, kZ, PhotonGather{k, 0.0f}, hinted);
    for (int c = 0; c < 3; ++c) EXPECT_EQ(a.value[c], b.value[c]) << q;
    std::vector<std::pair<float, size_t>> all;
    for (size_t i = 0; i < map.size(); ++i) {
      const Vec3 d = map.photons()[i].position - at;
      all.push_back({glm::dot(d, d), i});
    }
    std::sort(all.begin(), all.end());
    const double r2 = all[k - 1].first;
    double sum = 0.0;
    for (int i = 0; i < k; ++i) sum += (1.0 - all[i].first / r2) * map.photons()[all[i].second].power.color().r;
    const double expected = sum * 0.8 / kPi * 2.0 / (kPi * r2);
    EXPECT_NEAR(a.value.r / expected, 1.0, 1e-5) << q;
  }
}

const PhotonGather kFixed{0, 0.2f}, kNearest{400, 0.0f};

TEST(SurfaceShare, AConcaveEdgeLeavesTheFloorsDensityUnbiased) {
  // A floor (y = 0, x in [0, 1]) meeting a wall (x = 0) with photons on both: at the
  // edge the disc is half floor. Without the wall's photons (nothing marks the edge)
  // the estimate is half the density there, as it always was.
  const Face floor{Vec3(0, 0, -1), kX, kZ, 1.0f, 2.0f, kY}, wall{Vec3(0, 0, -1), kY, kZ, 1.0f, 2.0f, kX};
  const IndirectPhotonMap room = gridMap({floor, wall}), bare = gridMap({floor});
  for (const PhotonGather& g : {kFixed, kNearest}) {
    for (float d : {0.0f, 0.02f, 0.05f, 0.1f, 0.15f, 0.3f}) {
      EXPECT_NEAR(ratio(room, Vec3(d, 0, 0), kY, g), 1.0, 0.01) << "k " << g.k << " d " << d;
    }
    EXPECT_NEAR(ratio(bare, Vec3(0, 0, 0), kY, g), 0.5, 0.02) << "k " << g.k;
  }
}

TEST(SurfaceShare, ARoomCornerAndABoxTopAreUnbiasedToo) {
  // Two walls (x = 0, z = 0) over a floor: a point near the corner.
  const Face floor{Vec3(0, 0, 0), kX, kZ, 1.0f, 1.0f, kY}, wallX{Vec3(0, 0, 0), kY, kZ, 1.0f, 1.0f, kX},
             wallZ{Vec3(0, 0, 0), kX, kY, 1.0f, 1.0f, kZ};
  const IndirectPhotonMap corner = gridMap({floor, wallX, wallZ});
  for (const PhotonGather& g : {kFixed, kNearest}) {
    EXPECT_NEAR(ratio(corner, Vec3(0.0f, 0, 0.0f), kY, g), 1.0, 0.02) << "k " << g.k;
    EXPECT_NEAR(ratio(corner, Vec3(0.03f, 0, 0.07f), kY, g), 1.0, 0.02) << "k " << g.k;
  }
  // A convex edge: a box's top (y = 0, x in [-1, 0]) and its side (x = 0, facing +x)
  // below it. The side's photons lie under the top's plane, on the other side of
  // their own plane from the query: the cut falls at the edge all the same.
  const Face top{Vec3(-1, 0, -1), kX, kZ, 1.0f, 2.0f, kY}, side{Vec3(0, -1, -1), kY, kZ, 1.0f, 2.0f, kX};
  const IndirectPhotonMap box = gridMap({top, side});
  for (const PhotonGather& g : {kFixed, kNearest}) {
    for (float d : {0.0f, 0.05f, 0.12f}) {
      EXPECT_NEAR(ratio(box, Vec3(-d, 0, 0), kY, g), 1.0, 0.01) << "k " << g.k << " d " << d;
    }
  }
}

TEST(SurfaceShare, AThinWallKeepsTheFloorBeyondItOut) {
  // The floor runs under a thin wall at x = 0; the far side (x < 0) is lit ten times
  // brighter. The near side's wall face (normal +x) cuts the disc at the wall, so the
  // far side's photons, in the query's own plane and facing the same way, stay out.
  const Face nearFloor{Vec3(0, 0, -1), kX, kZ, 1.0f, 2.0f, kY},
             farFloor{Vec3(-1, 0, -1), kX, kZ, 1.0f, 2.0f, kY, 10.0f},
             wall{Vec3(0, 0, -1), kY, kZ, 1.0f, 2.0f, kX};
  const IndirectPhotonMap map = gridMap({nearFloor, farFloor, wall});
  for (const PhotonGather& g : {kFixed, kNearest}) {
    for (float d : {0.01f, 0.05f, 0.1f}) {
      EXPECT_NEAR(ratio(map, Vec3(d, 0, 0), kY, g), 1.0, 0.01) << "k " << g.k << " d " << d;
    }
  }
}

TEST(SurfaceShare, ACurvedSurfaceTurningAwayCutsNothing) {
  // 20000 photons spread evenly over a unit sphere (a Fibonacci lattice), gathered
  // within 1.2: the disc reaches 74 degrees around the sphere, so photons 60-74
  // degrees away stand at an angle to the query, each on its own tangent plane. No
  // two agree on a plane: the estimate is the plain kernel sum over the photons
  // facing the query's way, computed here by brute force.
  const int n = 20000;
  const float phi = 0.001f, r = 1.2f;
  PhotonArray<IndirectPhoton> photons;
  for (int i = 0; i < n; ++i) {
    const float z = 1.0f - (2.0f * i + 1.0f) / n, rho = std::sqrt(1.0f - z * z);
    const float a = 2.399963f * i;  // the golden angle
    const Vec3 p(rho * std::cos(a), rho * std::sin(a), z);
    photons.push_back({p, Color(phi), encodeOctahedral(-p), encodeOctahedral(p)});
  }
  IndirectPhotonMap map;
  map.build(photons);
  const Vec3 q = glm::normalize(Vec3(0.3f, -0.2f, 0.9f));
  double plain = 0.0;
  for (const IndirectPhoton& ph : photons) {
    const float d2 = glm::dot(ph.position - q, ph.position - q);
    if (d2 < r * r && glm::dot(decodeOctahedral(ph.normal), q) > 0.5f)
      plain += 2.0 / (kPi * r * r) * (1.0 - d2 / (r * r)) * ph.power.color().g;
  }
  Bsdf white;
  white.type = BsdfType::Opaque;
  white.diffuse = Color(1.0f);
  GatherScratch scratch;
  const RadianceEstimate e = photonRadiance(map, white, BsdfFrame{q, q, true}, q, q, PhotonGather{0, r}, scratch);
  EXPECT_NEAR(e.value.g * kPi / plain, 1.0, 1e-4);
}

TEST(SurfaceShare, PhotonsFacingAwayOrAlongTheSurfaceCutNothing) {
  const Vec3 p(0, 0, 0), n = kY;
  SurfaceCuts cuts(p, n, 0.1f);
  cuts.add(Vec3(0.05f, -0.001f, 0), -kY, -1.0f);  // the far side of a thin floor
  cuts.add(Vec3(0.05f, 0.0f, 0), kY, 1.0f);        // the floor itself
  cuts.add(Vec3(0.5f, 0.0f, 0), -kX, 0.0f);        // a wall beyond the radius
  cuts.add(Vec3(0.5f, 0.05f, 0), -kX, 0.0f);
  cuts.add(Vec3(0.04f, 0.01f, 0.02f), -kX, 0.0f);  // one photon of a wall: no plane yet
  SurfaceCuts lone = cuts;
  lone.finish();
  EXPECT_EQ(lone.count(), 0);
  EXPECT_EQ(lone.share(), 1.0f);
  // A second photon of the wall, 0.064 from the first: one cut, at the wall's distance.
  cuts.add(Vec3(0.04f, 0.05f, -0.03f), -kX, 0.0f);
  cuts.finish();
  EXPECT_EQ(cuts.count(), 1);
  EXPECT_NEAR(cuts.share(), 1.0 - kernelMassBeyond(0.4), 1e-6);
  EXPECT_TRUE(cuts.keeps(Vec3(0.039f, 0, 0.05f)));
  EXPECT_FALSE(cuts.keeps(Vec3(0.041f, 0, 0.05f)));
}

}  // namespace
}  // namespace penumbra
