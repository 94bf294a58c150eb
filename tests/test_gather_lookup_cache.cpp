// The precomputed lookup cache against the exact estimators it replaces: a uniformly
// lit plane (analytic irradiance), a half-shadowed plane (the gate never contradicts
// the truth), a thin wall's two sides, a thin box's exit hits, and points far from any
// photon.
#include "gather/lookup_cache.h"
#include "gather/photon_map.h"
#include "core/rng.h"
#include <gtest/gtest.h>
#include <tbb/enumerable_thread_specific.h>
#include <tbb/parallel_for.h>
#include <cmath>
#include <memory>

namespace penumbra {
namespace {

// n x n photons jittered over the unit square in the plane z = 0, facing `normal`.
PhotonArray<IndirectPhoton> planePhotons(int n, const Vec3& normal, const Color& power, uint64_t seed) {
  PhotonArray<IndirectPhoton> out;
  Rng rng(seed);
  for (int y = 0; y < n; ++y)
    for (int x = 0; x < n; ++x) {
      IndirectPhoton p;
      p.position = Vec3((x + rng.uniform()) / n, (y + rng.uniform()) / n, 0.0f);
      p.power = power;
      p.direction = encodeOctahedral(-normal);
      p.normal = encodeOctahedral(normal);
      out.push_back(p);
    }
  return out;
}

// Shadow photons of light 0 over the unit square: direct where x < edge, else `beyond`.
PhotonArray<ShadowPhoton> halfShadow(int n, float edge, uint8_t beyond, const Vec3& normal) {
  PhotonArray<ShadowPhoton> out;
  Rng rng(11);
  for (int y = 0; y < n; ++y)
    for (int x = 0; x < n; ++x) {
      ShadowPhoton p{};
      p.position = Vec3((x + rng.uniform()) / n, (y + rng.uniform()) / n, 0.0f);
      p.normal = encodeOctahedral(normal);
      p.light = 0;
      p.shadow = p.position.x < edge ? uint8_t(kDirect) : beyond;
      out.push_back(p);
    }
  return out;
}

// A cache of gate verdicts alone over `map`, and the verdict of light 0 at p (facing +z).
LookupCache gateCache(const ShadowPhotonMap& map, float cellSize, bool glassBlocks = false) {
  LookupCacheParams params;
  params.gate = true;
  params.cellSize = cellSize;
  params.gateParams.glassBlocks = glassBlocks;
  LookupCache cache;
  cache.build(&map, nullptr, params);
  return cache;
}
GateVerdict verdictAt(const LookupCache& cache, const Vec3& p) {
  LookupCache::Answer a = cache.find(p, Vec3(0, 0, 1));
  return a.verdicts ? static_cast<GateVerdict>(a.verdicts[0]) : GateVerdict::Mixed;
}

TEST(LookupCache, UniformPlaneMatchesTheExactDensityAndTheAnalyticIrradiance) {
  const int n = 300;  // 90k photons of power 1e-4 over 1 m^2: irradiance 9 W/m^2
  IndirectPhotonMap map;
  map.build(planePhotons(n, Vec3(0, 0, 1), Color(1e-4f), 3));
  LookupCacheParams params;
  params.indirect = CachedIndirect::Density;
  params.k = 100;
  params.cellSize = cacheCellSize(&map, params.k, nullptr, 0, 1.0f);
  ASSERT_GT(params.cellSize, 0.0f);
  LookupCache cache;
  cache.build(nullptr, &map, params);
  ASSERT_FALSE(cache.empty());
  EXPECT_FALSE(cache.hasGate());
  // Fewer cells than photons / 16: the precompute costs far less than the gathers.
  EXPECT_LE(cache.records() * 16, map.size());

  GatherScratch s;
  Rng rng(5);
  double worst = 0.0;
  for (int i = 0; i < 200; ++i) {
    const Vec3 p(0.2f + 0.6f * rng.uniform(), 0.2f + 0.6f * rng.uniform(), 0.0f);
    LookupCache::Answer a = cache.find(p, Vec3(0, 0, 1));
    ASSERT_TRUE(a.hasIndirect);
    const float exact = map.density(p, Vec3(0, 0, 1), params.k, 0.0f, s).value.x;
    EXPECT_NEAR(exact, 9.0f, 9.0f * 0.15f);     // the estimator itself: noisy but unbiased
    EXPECT_NEAR(a.indirect.x, 9.0f, 9.0f * 0.1f);  // the cache: a smoothed version of it
    worst = std::max(worst, std::abs(double(a.indirect.x) - exact) / exact);
  }
  EXPECT_LT(worst, 0.15);
}

TEST(LookupCache, ClassicEstimateOfAConstantPowerIsAThirdOfIt) {
  IndirectPhotonMap map;
  map.build(planePhotons(200, Vec3(0, 0, 1), Color(0.25f, 0.5f, 0.75f), 4));
  LookupCacheParams params;
  params.indirect = CachedIndirect::Classic;
  params.k = 50;
  params.cellSize = 0.05f;
  LookupCache cache;
  cache.build(nullptr, &map, params);
  LookupCache::Answer a = cache.find(Vec3(0.5f, 0.31f, 0.0f), Vec3(0, 0, 1));
  ASSERT_TRUE(a.hasIndirect);
  // The weights 1 - d/d_max sum to about k/3, over k photons: the average is ~power/3.
  GatherScratch s;
  Color exact = map.classic(Vec3(0.5f, 0.31f, 0.0f), Vec3(0, 0, 1), 50, 0.0f, s).value;
  EXPECT_NEAR(a.indirect.z / a.indirect.x, 3.0f, 1e-3f);
  EXPECT_NEAR(a.indirect.y, 0.5f / 3.0f, 0.05f * 0.5f / 3.0f);
  EXPECT_NEAR(exact.y, 0.5f / 3.0f, 0.05f * 0.5f / 3.0f);
}

TEST(LookupCache, GateNeverContradictsTheTruthAndIsConfidentAwayFromTheEdge) {
  ShadowPhotonMap map;
  map.build(halfShadow(400, 0.5f, kShadowOpaque, Vec3(0, 0, 1)), 1);
  const float cellSize = 0.02f;
  const LookupCache cache = gateCache(map, cellSize);
  ASSERT_TRUE(cache.hasGate());
  int lit = 0, shadowed = 0, mixed = 0;
  Rng rng(9);
  for (int i = 0; i < 4000; ++i) {
    const Vec3 p(0.05f + 0.9f * rng.uniform(), 0.05f + 0.9f * rng.uniform(), 0.0f);
    LookupCache::Answer a = cache.find(p, Vec3(0, 0, 1));
    ASSERT_NE(a.verdicts, nullptr);
    const auto v = static_cast<GateVerdict>(a.verdicts[0]);
    if (v == GateVerdict::Lit) { EXPECT_LT(p.x, 0.5f) << p.x; ++lit; }
    if (v == GateVerdict::Shadowed) { EXPECT_GE(p.x, 0.5f) << p.x; ++shadowed; }
    if (v == GateVerdict::Mixed) {
      // Only the band of cells around the edge is undecided: <= 2 cells each side.
      EXPECT_LT(std::abs(p.x - 0.5f), 2.0f * cellSize + 1e-3f) << p.x;
      ++mixed;
    }
  }
  EXPECT_GT(lit, 1500);
  EXPECT_GT(shadowed, 1500);
  EXPECT_GT(mixed, 0);
}

TEST(LookupCache, WhereThePhotonsAreSparseTheVoteLooksTwiceAsFar) {
  // One photon per 0.05 x 0.05 and cells of 0.03: the 3 x 3 cells around a point hold
  // ~3 voters, under the quorum of 8, and the 5 x 5 around it ~9, which vote where
  // the nearer ones agree. A point whose own cell holds no photon (a third of them)
  // answers from the nearest cell around it that does.
  ShadowPhotonMap map;
  map.build(halfShadow(20, 0.5f, kShadowOpaque, Vec3(0, 0, 1)), 1);
  const float cellSize = 0.03f;
  const LookupCache cache = gateCache(map, cellSize);
  int decided = 0, far = 0;
  for (int ix = 0; ix < 60; ++ix)
    for (int iy = 0; iy < 60; ++iy) {
      const Vec3 p(0.1f + 0.8f * (ix + 0.5f) / 60.0f, 0.1f + 0.8f * (iy + 0.5f) / 60.0f, 0.0f);
      const LookupCache::Answer a = cache.find(p, Vec3(0, 0, 1));
      ASSERT_NE(a.verdicts, nullptr) << p.x << " " << p.y;
      const auto v = static_cast<GateVerdict>(a.verdicts[0]);
      // Never against the truth: every voter lies within 2 cells of the point's cell.
      if (v == GateVerdict::Lit) {
        EXPECT_LT(p.x, 0.5f) << p.x;
      }
      if (v == GateVerdict::Shadowed) {
        EXPECT_GE(p.x, 0.5f) << p.x;
      }
      if (std::abs(p.x - 0.5f) > 3.0f * cellSize) {
        ++far;
        if (v != GateVerdict::Mixed) ++decided;
      }
    }
  EXPECT_GT(decided, 0.8 * far) << decided << " of " << far;
}

TEST(LookupCache, AnEmptyCellAnswersFromTheNearestCellAroundIt) {
  // Lit photons over the unit square but for a hole of 0.1 x 0.1 at its centre, with
  // cells of 0.025: the hole's points answer from a cell at most one away, its middle
  // (two cells from any photon) not at all, and the plane's far side never.
  PhotonArray<ShadowPhoton> photons;
  for (const ShadowPhoton& ph : halfShadow(120, 2.0f, kShadowOpaque, Vec3(0, 0, 1)))
    if (std::abs(ph.position.x - 0.5f) > 0.05f || std::abs(ph.position.y - 0.5f) > 0.05f) photons.push_back(ph);
  ShadowPhotonMap map;
  map.build(std::move(photons), 1);
  const float cellSize = 0.025f;
  const LookupCache cache = gateCache(map, cellSize);
  int inHole = 0, answered = 0;
  for (int ix = 0; ix < 40; ++ix)
    for (int iy = 0; iy < 40; ++iy) {
      const Vec3 p(0.45f + 0.1f * (ix + 0.5f) / 40.0f, 0.45f + 0.1f * (iy + 0.5f) / 40.0f, 0.0f);
      ++inHole;
      const LookupCache::Answer a = cache.find(p, Vec3(0, 0, 1));
      EXPECT_EQ(cache.find(p, Vec3(0, 0, -1)).verdicts, nullptr);
      if (!a.verdicts) continue;
      ++answered;
      EXPECT_EQ(static_cast<GateVerdict>(a.verdicts[0]), GateVerdict::Lit) << p.x << " " << p.y;
    }
  // Cells of the hole one away from photons answer: all but its middle.
  EXPECT_GT(answered, inHole / 2);
  EXPECT_LT(answered, inHole);
  EXPECT_EQ(cache.find(Vec3(0.5f, 0.5f, 0.0f), Vec3(0, 0, 1)).verdicts, nullptr);
}

TEST(LookupCache, ACellWithNoVoterOfItsOwnIsNeverCalledShadowed) {
  // Light 1's photons cover the plane; light 0's (all behind an occluder, or all
  // direct) cover it but for a hole two 0.05 cells wide around (0.5, 0.5), which
  // holds the cell of its centre whole. That cell has a record (light 1's photons)
  // and no voter for light 0: its neighbours alone may call it lit, never shadowed.
  for (uint8_t kind : {uint8_t(kShadowOpaque), uint8_t(kDirect)}) {
    PhotonArray<ShadowPhoton> photons;
    for (ShadowPhoton ph : halfShadow(200, -1.0f, kind, Vec3(0, 0, 1))) {
      ph.light = 1;
      photons.push_back(ph);
      ph.light = 0;
      const bool hole = std::abs(ph.position.x - 0.5f) < 0.05f && std::abs(ph.position.y - 0.5f) < 0.05f;
      if (!hole) photons.push_back(ph);
    }
    ShadowPhotonMap map;
    map.build(std::move(photons), 2);
    LookupCacheParams params;
    params.gate = true;
    params.cellSize = 0.05f;
    LookupCache cache;
    cache.build(&map, nullptr, params);
    const GateVerdict around = kind == kDirect ? GateVerdict::Lit : GateVerdict::Shadowed;
    const LookupCache::Answer outside = cache.find(Vec3(0.3f, 0.3f, 0.0f), Vec3(0, 0, 1));
    ASSERT_NE(outside.verdicts, nullptr);
    EXPECT_EQ(static_cast<GateVerdict>(outside.verdicts[0]), around);
    const LookupCache::Answer in = cache.find(Vec3(0.5f, 0.5f, 0.0f), Vec3(0, 0, 1));
    ASSERT_NE(in.verdicts, nullptr);
    EXPECT_EQ(static_cast<GateVerdict>(in.verdicts[1]), around);
    EXPECT_EQ(static_cast<GateVerdict>(in.verdicts[0]), kind == kDirect ? GateVerdict::Lit : GateVerdict::Mixed);
  }
}

TEST(LookupCache, GlassShadowIsMixedUnlessGlassBlocks) {
  ShadowPhotonMap map;
  map.build(halfShadow(200, 0.5f, kShadowGlass, Vec3(0, 0, 1)), 1);
  const Vec3 behind(0.8f, 0.5f, 0.0f), front(0.2f, 0.5f, 0.0f);
  const LookupCache classic = gateCache(map, 0.03f);
  EXPECT_EQ(verdictAt(classic, behind), GateVerdict::Mixed);
  EXPECT_EQ(verdictAt(classic, front), GateVerdict::Lit);
  // The physical model: glass is a shadow.
  EXPECT_EQ(verdictAt(gateCache(map, 0.03f, /*glassBlocks=*/true), behind), GateVerdict::Shadowed);
}

TEST(LookupCache, ThinWallSidesKeepTheirOwnAnswers) {
  // Both sides of the plane z = 0: the +z side bright and lit, the -z side dim and dark.
  PhotonArray<IndirectPhoton> photons = planePhotons(200, Vec3(0, 0, 1), Color(1e-4f), 1);
  for (const IndirectPhoton& p : planePhotons(200, Vec3(0, 0, -1), Color(1e-5f), 2)) photons.push_back(p);
  IndirectPhotonMap indirect;
  indirect.build(std::move(photons));
  PhotonArray<ShadowPhoton> shadow = halfShadow(200, 2.0f, kShadowOpaque, Vec3(0, 0, 1));  // all direct
  for (ShadowPhoton p : halfShadow(200, -1.0f, kShadowOpaque, Vec3(0, 0, -1))) shadow.push_back(p);  // all shadow
  ShadowPhotonMap gate;
  gate.build(std::move(shadow), 1);
  LookupCacheParams params;
  params.indirect = CachedIndirect::Density;
  params.k = 50;
  params.gate = true;
  params.cellSize = 0.04f;
  LookupCache cache;
  cache.build(&gate, &indirect, params);
  const Vec3 p(0.5f, 0.5f, 0.0f);
  LookupCache::Answer up = cache.find(p, Vec3(0, 0, 1)), down = cache.find(p, Vec3(0, 0, -1));
  ASSERT_TRUE(up.hasIndirect && down.hasIndirect);
  // Ten times the power on the +z side; mixing the sides would give a ratio near 1.
  EXPECT_NEAR(up.indirect.x / down.indirect.x, 10.0f, 2.5f);
  EXPECT_EQ(static_cast<GateVerdict>(up.verdicts[0]), GateVerdict::Lit);
  EXPECT_EQ(static_cast<GateVerdict>(down.verdicts[0]), GateVerdict::Shadowed);
}

// A box thinner than a cell, lit on its front face (z = 0, facing +z): every line that
// meets the front face leaves through the back face 0.02 behind it, from behind, with
// its normal turned to face the light, so +z too. Those exit hits vote only for points
// seen from behind (inside the box); without the side they made the front face mixed.
TEST(LookupCache, AThinBoxsExitHitsVoteOnlyOnTheSideTheyMet) {
  auto box = [](bool markBackSide) {
    PhotonArray<ShadowPhoton> photons = halfShadow(150, 2.0f, kShadowOpaque, Vec3(0, 0, 1));  // all direct
    for (ShadowPhoton p : halfShadow(150, -1.0f, kShadowOpaque, Vec3(0, 0, 1))) {  // all behind
      p.position.z = -0.02f;
      p.backSide = markBackSide;
      photons.push_back(p);
    }
    ShadowPhotonMap map;
    map.build(std::move(photons), 1);
    return map;
  };
  const ShadowPhotonMap sided = box(true), unsided = box(false);
  const LookupCache cache = gateCache(sided, 0.1f), without = gateCache(unsided, 0.1f);
  GateParams params;
  GatherScratch scratch;
  Rng rng(19);
  for (int i = 0; i < 50; ++i) {
    const Vec3 front(0.2f + 0.6f * rng.uniform(), 0.2f + 0.6f * rng.uniform(), 0.0f);
    const Vec3 inside(front.x, front.y, -0.02f);
    EXPECT_EQ(verdictAt(cache, front), GateVerdict::Lit) << "front " << i;
    const LookupCache::Answer back = cache.find(inside, Vec3(0, 0, 1), /*backSide=*/true);
    ASSERT_NE(back.verdicts, nullptr);
    EXPECT_EQ(static_cast<GateVerdict>(back.verdicts[0]), GateVerdict::Shadowed) << "inside " << i;
    EXPECT_EQ(sided.classify(front, Vec3(0, 0, 1), 0, params, scratch), GateVerdict::Lit) << "exact front " << i;
    EXPECT_EQ(sided.classify(inside, Vec3(0, 0, 1), 0, params, scratch, true), GateVerdict::Shadowed)
        << "exact inside " << i;
    // The same photons without their side: the exit hits vote on the front face.
    EXPECT_EQ(verdictAt(without, front), GateVerdict::Mixed) << "unsided " << i;
    EXPECT_EQ(unsided.classify(front, Vec3(0, 0, 1), 0, params, scratch), GateVerdict::Mixed) << "unsided exact " << i;
  }
}

TEST(LookupCache, NoCellFarFromThePhotons) {
  IndirectPhotonMap map;
  map.build(planePhotons(50, Vec3(0, 0, 1), Color(1.0f), 1));
  LookupCacheParams params;
  params.indirect = CachedIndirect::Classic;
  params.cellSize = 0.05f;
  LookupCache cache;
  cache.build(nullptr, &map, params);
  EXPECT_FALSE(cache.find(Vec3(0.5f, 0.5f, 3.0f), Vec3(0, 0, 1)).hasIndirect);
  EXPECT_FALSE(cache.find(Vec3(-40.0f, 0.5f, 0.0f), Vec3(0, 0, 1)).hasIndirect);
  EXPECT_FALSE(cache.find(Vec3(0.5f, 0.5f, 0.0f), Vec3(1, 0, 0)).hasIndirect);  // no such surface
  EXPECT_TRUE(cache.find(Vec3(0.5f, 0.5f, 0.0f), Vec3(0, 0, 1)).hasIndirect);
  EXPECT_EQ(cache.find(Vec3(0.5f, 0.5f, 0.0f), Vec3(0, 0, 1)).verdicts, nullptr);  // no gate
}

TEST(LookupCache, CellSizeKeepsSixteenPhotonsPerCell) {
  // k photons within r: with k = 50 a cell of 0.5 r would hold ~4; it grows to >= 16.
  EXPECT_NEAR(cacheCellSize(1.0f, 50, 0.5f), std::sqrt(16.0f * kPi / 50.0f), 1e-5f);
  EXPECT_FLOAT_EQ(cacheCellSize(1.0f, 400, 0.5f), 0.5f);
  EXPECT_EQ(cacheCellSize(0.0f, 50, 1.0f), 0.0f);
}

}  // namespace
}  // namespace penumbra

namespace penumbra {
namespace {

// A point whose layer holds no cell (here: 2.5 cells above a lit plane) is answered by
// its own cell's estimate at the cell's centre, computed once and kept, the same value
// whichever thread asks first.
TEST(LookupCache, APointWithNoCellNearGetsItsOwnCellsEstimateOnceForEveryThread) {
  IndirectPhotonMap map;
  map.build(planePhotons(200, Vec3(0, 0, 1), Color(1e-4f), 9));
  LookupCacheParams params;
  params.indirect = CachedIndirect::Density;
  params.k = 50;
  params.cellSize = cacheCellSize(&map, params.k, nullptr, 0, 1.0f);
  auto makeCache = [&] {
    auto cache = std::make_unique<LookupCache>();
    cache->build(nullptr, &map, params);
    return cache;
  };
  const auto cache = makeCache();
  const float h = 2.5f * cache->cellSize();
  const Vec3 up(0, 0, 1);
  GatherScratch s;
  const Vec3 p(0.51f, 0.49f, h);
  ASSERT_FALSE(cache->find(p, up).hasIndirect);
  const Color lazy = cache->lazyIndirect(map, p, up, s);
  const Color exact = map.density(cache->cellCentreOf(p), up, params.k, params.maxRadius, s).value;
  EXPECT_EQ(lazy, exact);  // the estimator itself, at the cell's centre
  EXPECT_GT(lazy.r, 0.0f);
  EXPECT_EQ(cache->lazyCells(), 1u);
  // Anywhere in the same cell: the kept value, not a new gather.
  const Vec3 q = cache->cellCentreOf(p) + Vec3(0.3f * cache->cellSize(), -0.2f * cache->cellSize(), 0.0f);
  EXPECT_EQ(cache->lazyIndirect(map, q, up, s), lazy);
  EXPECT_EQ(cache->lazyCells(), 1u);

  // 20,000 points over ~2,500 cells asked from every thread at once, against one thread
  // asking a fresh cache in order: the same values, bit for bit.
  std::vector<Vec3> points;
  Rng rng(4);
  for (int i = 0; i < 20000; ++i) points.push_back(Vec3(rng.uniform(), rng.uniform(), h));
  std::vector<Color> parallel(points.size()), serial(points.size());
  const auto fresh = makeCache();
  tbb::enumerable_thread_specific<GatherScratch> scratch;
  tbb::parallel_for(size_t(0), points.size(), [&](size_t i) {
    parallel[i] = fresh->lazyIndirect(map, points[i], up, scratch.local());
  });
  const auto inOrder = makeCache();
  for (size_t i = 0; i < points.size(); ++i) serial[i] = inOrder->lazyIndirect(map, points[i], up, s);
  EXPECT_EQ(parallel, serial);
  // Which few keys a full probe run leaves unkept depends on the order they arrive
  // in (here every point misses, far beyond the table's design load); values never do.
  const double kept = double(fresh->lazyCells()), keptInOrder = double(inOrder->lazyCells());
  EXPECT_NEAR(kept, keptInOrder, 0.01 * keptInOrder);
  EXPECT_LT(inOrder->lazyCells(), points.size() / 4);  // kept: far fewer gathers than points
}

}  // namespace
}  // namespace penumbra
