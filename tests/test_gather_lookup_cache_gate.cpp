// The lookup cache's gate verdicts against the truth they stand for: a half-shadowed
// plane (never contradicted, confident away from the edge), sparse photons, empty
// cells, cells without voters of their own, glass, and a thin box's exit hits.
#include "gather/lookup_cache/lookup_cache.h"
#include "gather/photon_map.h"
#include "support/cache_photons.h"
#include <gtest/gtest.h>

namespace penumbra {
namespace {

using testing::halfShadow;

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

}  // namespace
}  // namespace penumbra
