// Hinted kNN (each thread's remembered radii) must return exactly what a cold
// search and a brute-force scan return, in any query order and with any hint.
#include "gather/photon_map.h"
#include "support/brute_knn.h"
#include <gtest/gtest.h>
#include <tbb/global_control.h>
#include <algorithm>
#include <array>
#include <cmath>

namespace penumbra {
namespace {

// ---- exact (dist2, index) answers, with and without search hints -------------------

// The answer is defined as the k smallest (dist2, index) pairs, ascending: compare
// both arrays exactly, ties included.
template <class Map>
void expectExactKnn(const Map& map, const PhotonArray<IndirectPhoton>& photons, const Vec3& q,
                    size_t k, float maxRadius, GatherScratch& s, const char* what) {
  size_t n = map.knn(q, k, maxRadius, s);
  Brute b = bruteKnn(photons, q, k, maxRadius);
  ASSERT_EQ(n, b.d2.size()) << what << " k=" << k << " r=" << maxRadius;
  EXPECT_EQ(std::vector<float>(s.dist2.begin(), s.dist2.begin() + n), b.d2) << what;
  EXPECT_EQ(std::vector<uint32_t>(s.indices.begin(), s.indices.begin() + n), b.indices) << what;
}

// Query points along a smooth path (as a scan line visits them), or scattered.
std::vector<Vec3> querySequence(size_t n, bool coherent, uint64_t seed, float spread = 1.2f) {
  Rng rng(seed);
  std::vector<Vec3> out;
  Vec3 p(-0.9f, -0.3f, 0.2f);
  for (size_t i = 0; i < n; ++i) {
    if (coherent) {
      p += Vec3(0.013f, 0.004f * rng.uniform(), -0.002f);
      if (p.x > 1.1f) p = Vec3(-1.1f, p.y + 0.05f, p.z);
    } else {
      p = (Vec3(rng.uniform(), rng.uniform(), rng.uniform()) * 2.0f - 1.0f) * spread;
    }
    out.push_back(p);
  }
  return out;
}

struct HintCase {
  const char* name;
  PhotonArray<IndirectPhoton> cloud;
};
std::vector<HintCase> hintCases() {
  std::vector<HintCase> cases;
  cases.push_back({"random", randomCloud(6000, 21)});
  PhotonArray<IndirectPhoton> same(400, indirectAt(Vec3(0.1f, 0.2f, 0.3f)));
  for (int i = 0; i < 300; ++i) same.push_back(indirectAt(Vec3(-0.5f, 0.5f, 0.0f)));
  cases.push_back({"identical", same});
  PhotonArray<IndirectPhoton> line;  // equal spacing: many exactly tied distances
  for (int i = 0; i < 3000; ++i) line.push_back(indirectAt(Vec3(-1.0f + 0.001f * i, 0.25f, 0.0f)));
  cases.push_back({"collinear", line});
  PhotonArray<IndirectPhoton> grid;  // a lattice: ties at every shell
  for (int j = 0; j < 60; ++j)
    for (int i = 0; i < 60; ++i) grid.push_back(indirectAt(Vec3(i / 30.0f - 1.0f, j / 30.0f - 1.0f, 0.0f)));
  cases.push_back({"grid", grid});
  return cases;
}

TEST(KnnHinted, WarmHintsMatchBruteForceInAnyOrder) {
  for (const HintCase& c : hintCases()) {
    IndirectPhotonMap map;
    map.build(c.cloud);
    const auto& photons = map.photons();
    for (bool coherent : {true, false})
      for (float r : {0.0f, 0.15f}) {
        GatherScratch warm;  // one scratch for the whole sequence, as a render thread
        for (const Vec3& q : querySequence(150, coherent, 5)) {
          for (size_t k : {1, 16, 50}) expectExactKnn(map, photons, q, k, r, warm, c.name);
          if (::testing::Test::HasFailure()) return;
        }
        // For a coherent walk, the hints must have been used (and mostly worked).
        if (coherent && r == 0.0f) {
          EXPECT_GT(warm.hintedQueries, 300u) << c.name;
        }
      }
  }
}

TEST(KnnHinted, ForcedHintsOfAnySizeMatchBruteForce) {
  for (const HintCase& c : hintCases()) {
    IndirectPhotonMap map;
    map.build(c.cloud);
    const auto& photons = map.photons();
    for (const Vec3& q : querySequence(40, false, 8)) {
      for (size_t k : {1, 50}) {
        // The true k-th distance: a hint exactly at, below and above it.
        Brute b = bruteKnn(photons, q, k, 0.0f);
        const float rk = std::sqrt(b.d2.back());
        for (float hint : {rk, std::nextafter(rk, 0.0f), rk * 0.3f, 0.0f, rk * 1.01f, rk * 10.0f,
                           1e6f})
          for (float r : {0.0f, 0.1f, 0.6f}) {
            GatherScratch s;
            s.forcedHintRadius = hint;
            expectExactKnn(map, photons, q, k, r, s, c.name);
          }
      }
      if (::testing::Test::HasFailure()) return;
    }
  }
}

TEST(KnnHinted, ShadowMapWarmEqualsCold) {
  Rng rng(17);
  PhotonArray<ShadowPhoton> in;
  for (uint32_t i = 0; i < 20000; ++i) {
    ShadowPhoton ph{};
    ph.position = Vec3(rng.uniform(), rng.uniform(), 0.1f * rng.uniform());
    ph.normal = encodeOctahedral(Vec3(0, 0, 1));
    ph.light = static_cast<uint16_t>(i % 2);
    in.push_back(ph);
  }
  ShadowPhotonMap map;
  map.build(in, 2);
  GatherScratch warm;
  for (const Vec3& q0 : querySequence(300, true, 3)) {
    Vec3 q = q0 * 0.5f + Vec3(0.5f, 0.5f, 0.0f);
    for (uint32_t light : {0u, 1u}) {  // alternating lights share the scratch
      GatherScratch cold;
      cold.useHints = false;
      size_t nw = map.knn(q, light, 50, 0.0f, warm), nc = map.knn(q, light, 50, 0.0f, cold);
      ASSERT_EQ(nw, nc);
      for (size_t i = 0; i < nw; ++i) {
        ASSERT_EQ(warm.indices[i], cold.indices[i]);
        ASSERT_EQ(warm.dist2[i], cold.dist2[i]);
      }
    }
  }
  EXPECT_GT(warm.hintedQueries, 500u);
}

// The tracer's queries: classify() per light, classic()/density(), all from one
// scratch per thread. A warm scratch (hints from earlier queries, interleaved maps and
// lights) must give bit-identical results to a cold one, and the estimates must equal
// the estimators applied to the brute-force (dist2, index) neighbour list.
TEST(KnnHinted, GateAndEstimatesIdenticalWithWarmHints) {
  Rng rng(31);
  PhotonArray<ShadowPhoton> shadow;
  PhotonArray<IndirectPhoton> indirect;
  auto randomNormal = [&]() {
    Vec3 n(rng.uniform() - 0.5f, rng.uniform() - 0.5f, rng.uniform() * 0.6f);
    return glm::normalize(n + Vec3(0.0f, 0.0f, 0.2f));
  };
  for (int i = 0; i < 30000; ++i) {
    ShadowPhoton ph{};
    ph.position = Vec3(rng.uniform(), rng.uniform(), 0.05f * rng.uniform()) * 2.0f - 1.0f;
    ph.normal = encodeOctahedral(randomNormal());
    ph.light = static_cast<uint16_t>(i % 3);
    // Shadowed discs of different sizes per light: lit, shadowed and edge regions.
    ph.shadow = glm::length(Vec3(ph.position.x, ph.position.y, 0.0f)) < 0.3f * (ph.light + 1) ? 1 : 0;
    shadow.push_back(ph);
  }
  for (int i = 0; i < 20000; ++i) {
    IndirectPhoton ph = indirectAt(Vec3(rng.uniform(), rng.uniform(), 0.05f * rng.uniform()) * 2.0f - 1.0f);
    ph.normal = encodeOctahedral(randomNormal());
    ph.power = Color(rng.uniform(), rng.uniform(), rng.uniform());
    indirect.push_back(ph);
  }
  ShadowPhotonMap smap;
  smap.build(shadow, 3);
  IndirectPhotonMap imap;
  imap.build(indirect);
  GateParams params;
  params.minNormalCos = 0.3f;

  for (bool coherent : {false, true}) {
    GatherScratch warm;
    std::array<int, 3> verdicts{};
    for (const Vec3& q0 : querySequence(1000, coherent, 77, 1.0f)) {
      const Vec3 q(q0.x, q0.y, q0.z * 0.05f);
      const Vec3 n(0.0f, 0.0f, 1.0f);
      for (float maxR : {0.0f, 0.08f}) {
        params.maxRadius = maxR;
        for (uint32_t light = 0; light < 3; ++light) {
          GatherScratch cold;
          cold.useHints = false;
          GateVerdict w = smap.classify(q, n, light, params, warm);
          ASSERT_EQ(w, smap.classify(q, n, light, params, cold));
          ++verdicts[static_cast<int>(w)];
        }
        for (int k : {50, 200}) {
          GatherScratch cold;
          cold.useHints = false;
          // Reference: the estimators over the brute-force list.
          Brute b = bruteKnn(imap.photons(), q, static_cast<size_t>(k), maxR);
          GatherScratch ref;
          ref.indices = b.indices;
          ref.dist2 = b.d2;
          for (int density : {0, 1}) {
            auto est = [&](GatherScratch& s) {
              return density ? imap.density(q, n, k, maxR, s, 0.2f) : imap.classic(q, n, k, maxR, s, 0.2f);
            };
            IndirectEstimate ew = est(warm), ec = est(cold);
            IndirectEstimate er = density
                ? densityEstimate(imap.photons().data(), ref, b.d2.size(), n, 0.2f)
                : classicEstimate(imap.photons().data(), ref, b.d2.size(), n, 0.2f);
            for (const IndirectEstimate* e : {&ec, &er}) {
              ASSERT_EQ(ew.found, e->found);
              ASSERT_EQ(ew.dMax, e->dMax);
              ASSERT_EQ(ew.value, e->value);
            }
          }
        }
      }
    }
    EXPECT_GT(warm.hintedQueries, 4000u);
    // The scene exercises every verdict.
    EXPECT_GT(verdicts[0], 100);
    EXPECT_GT(verdicts[1], 100);
    EXPECT_GT(verdicts[2], 50);
  }
}

}  // namespace
}  // namespace penumbra
