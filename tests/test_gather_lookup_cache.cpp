// The precomputed lookup cache against the exact estimators it replaces: a uniformly
// lit plane (analytic irradiance), a constant power, a thin wall's two sides, points
// far from any photon and the lazy cells of points with no cell near.
#include "gather/lookup_cache/lookup_cache.h"
#include "gather/photon_map.h"
#include "support/cache_photons.h"
#include <gtest/gtest.h>
#include <tbb/enumerable_thread_specific.h>
#include <tbb/parallel_for.h>
#include <cmath>
#include <memory>

namespace penumbra {
namespace {

using testing::halfShadow;
using testing::planePhotons;

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
