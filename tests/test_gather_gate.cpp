// The shadow gate: verdicts from planes of direct/shadow photons, the voter minimum
// and the normal filter that keeps a thin wall's far side out of the vote.
#include "core/rng.h"
#include "gather/photon_map.h"
#include <gtest/gtest.h>
#include <vector>

namespace penumbra {
namespace {

const Vec3 kUp(0.0f, 0.0f, 1.0f);

// n photons on a jittered grid over [0,1]^2 at height z; shadowFn(i, x) decides the kind.
template <class ShadowFn>
void addPlane(PhotonArray<ShadowPhoton>& out, int side, float z, const Vec3& normal,
              uint16_t light, ShadowFn shadowFn, uint64_t seed) {
  Rng rng(seed);
  for (int j = 0; j < side; ++j)
    for (int i = 0; i < side; ++i) {
      ShadowPhoton ph{};
      ph.position = Vec3((i + rng.uniform()) / side, (j + rng.uniform()) / side, z);
      ph.normal = encodeOctahedral(normal);
      ph.light = light;
      ph.shadow = shadowFn(j * side + i, ph.position.x) ? 1 : 0;
      out.push_back(ph);
    }
}
auto allDirect = [](int, float) { return false; };
auto allShadow = [](int, float) { return true; };

GateVerdict classifyAt(const PhotonArray<ShadowPhoton>& photons, size_t lights, const Vec3& p,
                       const Vec3& n, uint32_t light, GateParams params = {}) {
  ShadowPhotonMap map;
  map.build(photons, lights);
  GatherScratch s;
  return map.classify(p, n, light, params, s);
}

TEST(Gate, PlaneOfDirectPhotonsIsLit) {
  PhotonArray<ShadowPhoton> ph;
  addPlane(ph, 100, 0.0f, kUp, 0, allDirect, 1);
  EXPECT_EQ(classifyAt(ph, 1, Vec3(0.5f, 0.5f, 0.0f), kUp, 0), GateVerdict::Lit);
  EXPECT_EQ(classifyAt(ph, 1, Vec3(0.0f, 1.0f, 0.0f), kUp, 0), GateVerdict::Lit);  // corner
}

TEST(Gate, PlaneOfShadowPhotonsIsShadowed) {
  PhotonArray<ShadowPhoton> ph;
  addPlane(ph, 100, 0.0f, kUp, 0, allShadow, 2);
  EXPECT_EQ(classifyAt(ph, 1, Vec3(0.5f, 0.5f, 0.0f), kUp, 0), GateVerdict::Shadowed);
}

// Behind glass alone the light is tinted, not blocked: the gate must hand such
// points to a shadow ray, even when every voter is a shadow photon.
TEST(Gate, ShadowBehindGlassOnlyAsksForARay) {
  PhotonArray<ShadowPhoton> ph;
  addPlane(ph, 100, 0.0f, kUp, 0, allShadow, 2);
  for (ShadowPhoton& p : ph) p.shadow = kShadowGlass;
  EXPECT_EQ(classifyAt(ph, 1, Vec3(0.5f, 0.5f, 0.0f), kUp, 0), GateVerdict::Mixed);
  // One glass-only photon among opaque-shadow voters is enough to ask.
  for (ShadowPhoton& p : ph) p.shadow = kShadowOpaque;
  EXPECT_EQ(classifyAt(ph, 1, Vec3(0.5f, 0.5f, 0.0f), kUp, 0), GateVerdict::Shadowed);
  ShadowPhotonMap map;
  map.build(ph, 1);
  GatherScratch scratch;
  ASSERT_EQ(map.knn(Vec3(0.5f, 0.5f, 0.0f), 0, 1, 0.0f, scratch), 1u);
  const auto range = map.photons(0);
  PhotonArray<ShadowPhoton> sorted(range.begin(), range.end());
  sorted[scratch.indices[0]].shadow = kShadowGlass;
  EXPECT_EQ(classifyAt(sorted, 1, Vec3(0.5f, 0.5f, 0.0f), kUp, 0), GateVerdict::Mixed);
}

TEST(Gate, HalfAndHalfIsMixedOnlyNearTheBoundary) {
  PhotonArray<ShadowPhoton> ph;
  addPlane(ph, 100, 0.0f, kUp, 0, [](int, float x) { return x > 0.5f; }, 3);
  // Interleaved kinds: every neighbourhood holds both.
  PhotonArray<ShadowPhoton> alternating;
  addPlane(alternating, 100, 0.0f, kUp, 0, [](int i, float) { return i % 2 == 1; }, 4);
  EXPECT_EQ(classifyAt(alternating, 1, Vec3(0.5f, 0.5f, 0.0f), kUp, 0), GateVerdict::Mixed);
  // A shadow edge at x = 0.5: on it Mixed, well away from it a clean verdict (50
  // photons at 10^4/unit^2 span a radius of ~0.04).
  EXPECT_EQ(classifyAt(ph, 1, Vec3(0.5f, 0.5f, 0.0f), kUp, 0), GateVerdict::Mixed);
  EXPECT_EQ(classifyAt(ph, 1, Vec3(0.3f, 0.5f, 0.0f), kUp, 0), GateVerdict::Lit);
  EXPECT_EQ(classifyAt(ph, 1, Vec3(0.7f, 0.5f, 0.0f), kUp, 0), GateVerdict::Shadowed);
}

// The map a photon stage builds leaves its trees out (precomputed lookups never read
// them); built later, they keep the photons in their order and vote as trees built at once.
TEST(Gate, TreesBuiltLaterKeepThePhotonsAndVoteAlike) {
  PhotonArray<ShadowPhoton> ph;
  addPlane(ph, 100, 0.0f, kUp, 0, [](int, float x) { return x > 0.5f; }, 3);
  addPlane(ph, 60, 0.0f, kUp, 1, [](int i, float) { return i % 3 == 0; }, 5);
  ShadowPhotonMap eager, later;
  eager.build(ph, 2);
  MapBuildOptions deferred;
  deferred.shadowTrees = false;
  later.build(ph, 2, deferred);
  EXPECT_TRUE(eager.hasTrees());
  EXPECT_FALSE(later.hasTrees());
  std::vector<Vec3> before;
  for (const ShadowPhoton& p : later.photons(0)) before.push_back(p.position);
  later.buildTrees();
  ASSERT_TRUE(later.hasTrees());
  size_t i = 0;
  for (const ShadowPhoton& p : later.photons(0)) ASSERT_EQ(p.position, before[i++]);
  GatherScratch s;
  for (int y = 0; y < 10; ++y)
    for (int x = 0; x < 10; ++x)
      for (uint32_t light : {0u, 1u}) {
        const Vec3 p((x + 0.5f) / 10.0f, (y + 0.5f) / 10.0f, 0.0f);
        EXPECT_EQ(later.classify(p, kUp, light, {}, s), eager.classify(p, kUp, light, {}, s)) << p.x << " " << p.y;
        const size_t n = later.knn(p, light, 20, 0.0f, s);
        std::vector<float> d(s.dist2.begin(), s.dist2.begin() + static_cast<long>(n));
        ASSERT_EQ(eager.knn(p, light, 20, 0.0f, s), n);
        for (size_t j = 0; j < n; ++j) EXPECT_EQ(d[j], s.dist2[j]);
      }
}

TEST(Gate, TooFewVotersIsMixed) {
  PhotonArray<ShadowPhoton> ph;
  addPlane(ph, 2, 0.0f, kUp, 0, allDirect, 5);  // 4 photons, minVoters 8
  EXPECT_EQ(classifyAt(ph, 1, Vec3(0.5f, 0.5f, 0.0f), kUp, 0), GateVerdict::Mixed);
  GateParams lenient;
  lenient.minVoters = 4;
  EXPECT_EQ(classifyAt(ph, 1, Vec3(0.5f, 0.5f, 0.0f), kUp, 0, lenient), GateVerdict::Lit);

  // Plenty of photons, but maxRadius keeps all but a few out of the vote.
  PhotonArray<ShadowPhoton> dense;
  addPlane(dense, 100, 0.0f, kUp, 0, allDirect, 6);
  GateParams tight;
  tight.maxRadius = 0.01f;  // ~3 photons inside at 10^4/unit^2
  EXPECT_EQ(classifyAt(dense, 1, Vec3(0.5f, 0.5f, 0.0f), kUp, 0, tight), GateVerdict::Mixed);
  tight.maxRadius = 0.1f;  // plenty
  EXPECT_EQ(classifyAt(dense, 1, Vec3(0.5f, 0.5f, 0.0f), kUp, 0, tight), GateVerdict::Lit);
}

TEST(Gate, NoPhotonsForTheLightIsMixed) {
  PhotonArray<ShadowPhoton> ph;
  addPlane(ph, 50, 0.0f, kUp, 0, allDirect, 7);
  EXPECT_EQ(classifyAt(ph, 2, Vec3(0.5f, 0.5f, 0.0f), kUp, 1), GateVerdict::Mixed);
  EXPECT_EQ(classifyAt(ph, 2, Vec3(0.5f, 0.5f, 0.0f), kUp, 5), GateVerdict::Mixed);
  EXPECT_EQ(classifyAt({}, 1, Vec3(0.0f), kUp, 0), GateVerdict::Mixed);
}

TEST(Gate, LightsAreJudgedSeparately) {
  PhotonArray<ShadowPhoton> ph;
  addPlane(ph, 80, 0.0f, kUp, 0, allDirect, 8);
  addPlane(ph, 80, 0.0f, kUp, 1, allShadow, 9);
  EXPECT_EQ(classifyAt(ph, 2, Vec3(0.5f, 0.5f, 0.0f), kUp, 0), GateVerdict::Lit);
  EXPECT_EQ(classifyAt(ph, 2, Vec3(0.5f, 0.5f, 0.0f), kUp, 1), GateVerdict::Shadowed);
}

// A wall 1 mm thick, shadowed on top and lit from below. Stored normals face where
// each photon arrived from: +z on the top face, -z on the bottom face. Querying the top
// (viewer above, n = +z), the bottom's photons are just as close and make up half the
// 50 nearest; the normal filter must keep them out, else the top would read Mixed.
TEST(Gate, ThinWallFarSideDoesNotVote) {
  PhotonArray<ShadowPhoton> ph;
  addPlane(ph, 100, 0.0005f, kUp, 0, allShadow, 10);               // top: in shadow
  addPlane(ph, 100, -0.0005f, Vec3(0, 0, -1), 0, allDirect, 11);  // bottom: lit from below
  const Vec3 top(0.5f, 0.5f, 0.0005f), bottom(0.5f, 0.5f, -0.0005f);
  EXPECT_EQ(classifyAt(ph, 1, top, kUp, 0), GateVerdict::Shadowed);
  EXPECT_EQ(classifyAt(ph, 1, bottom, -kUp, 0), GateVerdict::Lit);

  // The filter is what makes the difference: with it disabled (every photon votes)
  // the same query flips to Mixed.
  GateParams everyone;
  everyone.minNormalCos = -2.0f;
  EXPECT_EQ(classifyAt(ph, 1, top, kUp, 0, everyone), GateVerdict::Mixed);

  // Only far-side photons within reach: none votes, so too few voters -> Mixed, not Lit.
  PhotonArray<ShadowPhoton> farOnly;
  addPlane(farOnly, 100, -0.0005f, Vec3(0, 0, -1), 0, allDirect, 12);
  EXPECT_EQ(classifyAt(farOnly, 1, top, kUp, 0), GateVerdict::Mixed);
}

TEST(Gate, VoteRuleDirectly) {
  PhotonArray<ShadowPhoton> ph(10);
  std::vector<uint32_t> idx(10);
  for (uint32_t i = 0; i < 10; ++i) {
    ph[i].normal = encodeOctahedral(kUp);
    idx[i] = i;
  }
  GateParams p;
  EXPECT_EQ(voteGate(ph.data(), idx.data(), 10, kUp, p), GateVerdict::Lit);
  ph[9].shadow = 1;
  EXPECT_EQ(voteGate(ph.data(), idx.data(), 10, kUp, p), GateVerdict::Mixed);
  ph[9].normal = encodeOctahedral(Vec3(1, 0, 0));  // perpendicular: cos 0 < 0.5, no vote
  EXPECT_EQ(voteGate(ph.data(), idx.data(), 10, kUp, p), GateVerdict::Lit);
  ph[9].normal = encodeOctahedral(glm::normalize(Vec3(1, 0, 1)));  // cos 0.707: votes
  EXPECT_EQ(voteGate(ph.data(), idx.data(), 10, kUp, p), GateVerdict::Mixed);
  EXPECT_EQ(voteGate(ph.data(), idx.data(), 0, kUp, p), GateVerdict::Mixed);
  p.minVoters = 0;  // even then, zero voters is no evidence
  EXPECT_EQ(voteGate(ph.data(), idx.data(), 0, kUp, p), GateVerdict::Mixed);
}

}  // namespace
}  // namespace penumbra
