// The photon maps' kNN against a brute-force linear scan, including degenerate sets.
#include "core/rng.h"
#include "gather/morton.h"
#include "gather/photon_map.h"
#include <gtest/gtest.h>
#include <tbb/global_control.h>
#include <algorithm>
#include <array>
#include <cmath>
#include <set>

namespace penumbra {
namespace {

IndirectPhoton indirectAt(const Vec3& p) {
  return {p, Color(1.0f), encodeOctahedral(Vec3(0, 0, 1)), encodeOctahedral(Vec3(0, 0, 1))};
}

std::vector<IndirectPhoton> randomCloud(size_t n, uint64_t seed) {
  Rng rng(seed);
  std::vector<IndirectPhoton> out;
  for (size_t i = 0; i < n; ++i)
    out.push_back(indirectAt(Vec3(rng.uniform(), rng.uniform(), rng.uniform()) * 2.0f - 1.0f));
  return out;
}

// Squared distances the same way nanoflann's L2_Simple_Adaptor sums them, so ties and
// the radius cut-off agree to the bit.
float dist2(const Vec3& a, const Vec3& b) {
  float s = 0.0f;
  for (int i = 0; i < 3; ++i) s += (a[i] - b[i]) * (a[i] - b[i]);
  return s;
}

struct Brute {
  std::vector<float> d2;          // ascending, k nearest
  std::vector<uint32_t> indices;  // same order
};
template <class Photon>
Brute bruteKnn(const std::vector<Photon>& photons, const Vec3& q, size_t k, float maxRadius) {
  std::vector<std::pair<float, uint32_t>> all;
  for (size_t i = 0; i < photons.size(); ++i) {
    float d = dist2(photons[i].position, q);
    if (maxRadius > 0.0f && !(d < maxRadius * maxRadius)) continue;
    all.push_back({d, static_cast<uint32_t>(i)});
  }
  const size_t keep = std::min(k, all.size());
  std::partial_sort(all.begin(), all.begin() + keep, all.end());
  Brute b;
  for (size_t i = 0; i < std::min(k, all.size()); ++i) {
    b.d2.push_back(all[i].first);
    b.indices.push_back(all[i].second);
  }
  return b;
}

// Same distance list; same index set where the k-th distance is not tied with the
// (k+1)-th (otherwise which of the tied photons is returned is arbitrary).
template <class Map>
void expectMatchesBrute(const Map& map, const std::vector<IndirectPhoton>& photons,
                        const Vec3& q, size_t k, float maxRadius) {
  GatherScratch s;
  size_t n = map.knn(q, k, maxRadius, s);
  Brute b = bruteKnn(photons, q, k, maxRadius);
  ASSERT_EQ(n, b.d2.size()) << "k=" << k << " r=" << maxRadius;
  std::vector<float> got(s.dist2.begin(), s.dist2.begin() + n);
  EXPECT_TRUE(std::is_sorted(got.begin(), got.end()));
  EXPECT_EQ(got, b.d2);
  for (size_t i = 0; i < n; ++i)  // the reported distance is the photon's real one
    EXPECT_EQ(s.dist2[i], dist2(photons[s.indices[i]].position, q));
  std::set<float> distinct(b.d2.begin(), b.d2.end());
  if (distinct.size() == b.d2.size()) {
    std::set<uint32_t> gotIdx(s.indices.begin(), s.indices.begin() + n);
    std::set<Vec3, bool (*)(const Vec3&, const Vec3&)> gotPos(
        [](const Vec3& a, const Vec3& b) { return std::tie(a.x, a.y, a.z) < std::tie(b.x, b.y, b.z); });
    std::set<Vec3, bool (*)(const Vec3&, const Vec3&)> wantPos(gotPos.key_comp());
    for (uint32_t i : gotIdx) gotPos.insert(photons[i].position);
    for (uint32_t i : b.indices) wantPos.insert(photons[i].position);
    EXPECT_EQ(gotIdx.size(), n);
    EXPECT_EQ(gotPos, wantPos);
  }
}

class KnnRandom : public ::testing::TestWithParam<bool> {};

TEST_P(KnnRandom, MatchesBruteForceOn10kPoints) {
  IndirectPhotonMap map;
  map.build(randomCloud(10000, 7), {GetParam(), 24});
  ASSERT_EQ(map.size(), 10000u);
  const auto& photons = map.photons();  // the map's (possibly reordered) array
  Rng rng(99);
  for (int qi = 0; qi < 12; ++qi) {
    // Inside, on the boundary and outside the cloud.
    Vec3 q = (Vec3(rng.uniform(), rng.uniform(), rng.uniform()) * 2.0f - 1.0f) * 1.3f;
    for (size_t k : {1, 5, 50})
      for (float r : {0.0f, 0.05f, 0.2f, 10.0f}) expectMatchesBrute(map, photons, q, k, r);
  }
  // A query exactly on a stored photon finds it at distance 0 first.
  GatherScratch s;
  ASSERT_EQ(map.knn(photons[1234].position, 1, 0.0f, s), 1u);
  EXPECT_EQ(s.dist2[0], 0.0f);
  EXPECT_EQ(photons[s.indices[0]].position, photons[1234].position);
}
INSTANTIATE_TEST_SUITE_P(MortonOnOff, KnnRandom, ::testing::Bool());

TEST(Knn, RadiusBoundedReturnsFewerThanK) {
  IndirectPhotonMap map;
  map.build(randomCloud(10000, 3));
  GatherScratch s;
  // Expected count ~ 10000 * (4/3 pi 0.05^3) / 8 ~ 0.65: mostly 0 or 1, never 50.
  size_t n = map.knn(Vec3(0.0f), 50, 0.05f, s);
  EXPECT_LT(n, 10u);
  expectMatchesBrute(map, map.photons(), Vec3(0.0f), 50, 0.05f);
  // A radius enclosing nothing.
  EXPECT_EQ(map.knn(Vec3(5.0f), 50, 0.5f, s), 0u);
}

TEST(Knn, AllIdenticalPoints) {
  std::vector<IndirectPhoton> same(500, indirectAt(Vec3(0.25f, -1.0f, 3.0f)));
  IndirectPhotonMap map;
  map.build(same);
  GatherScratch s;
  ASSERT_EQ(map.knn(Vec3(0.25f, -1.0f, 3.0f), 50, 0.0f, s), 50u);
  for (size_t i = 0; i < 50; ++i) EXPECT_EQ(s.dist2[i], 0.0f);
  std::set<uint32_t> idx(s.indices.begin(), s.indices.begin() + 50);
  EXPECT_EQ(idx.size(), 50u);  // 50 different photons, not one photon 50 times
  expectMatchesBrute(map, map.photons(), Vec3(1.0f, 2.0f, 3.0f), 50, 0.0f);
  expectMatchesBrute(map, map.photons(), Vec3(0.25f, -1.0f, 3.5f), 50, 0.4f);  // all outside
  expectMatchesBrute(map, map.photons(), Vec3(0.25f, -1.0f, 3.5f), 600, 0.6f);  // all inside
}

TEST(Knn, CollinearPoints) {
  std::vector<IndirectPhoton> line;
  for (int i = 0; i < 2000; ++i) line.push_back(indirectAt(Vec3(0.5f, 0.001f * i, -2.0f)));
  IndirectPhotonMap map;
  map.build(line);
  for (Vec3 q : {Vec3(0.5f, 1.0f, -2.0f), Vec3(3.0f, 0.7003f, 1.0f), Vec3(0.5f, -1.0f, -2.0f)})
    for (size_t k : {1, 5, 50})
      for (float r : {0.0f, 0.02f}) expectMatchesBrute(map, map.photons(), q, k, r);
}

TEST(Knn, OnePointAndEmpty) {
  IndirectPhotonMap one;
  one.build({indirectAt(Vec3(1.0f, 2.0f, 3.0f))});
  GatherScratch s;
  ASSERT_EQ(one.knn(Vec3(0.0f), 50, 0.0f, s), 1u);
  EXPECT_FLOAT_EQ(s.dist2[0], 14.0f);
  EXPECT_EQ(s.indices[0], 0u);
  EXPECT_EQ(one.knn(Vec3(0.0f), 50, 3.0f, s), 0u);  // sqrt(14) > 3
  EXPECT_EQ(one.knn(Vec3(0.0f), 0, 0.0f, s), 0u);   // k = 0

  IndirectPhotonMap empty;
  empty.build({});
  EXPECT_TRUE(empty.empty());
  EXPECT_EQ(empty.knn(Vec3(0.0f), 50, 0.0f, s), 0u);
  EXPECT_EQ(empty.knn(Vec3(0.0f), 50, 1.0f, s), 0u);
  IndirectPhotonMap neverBuilt;
  EXPECT_EQ(neverBuilt.knn(Vec3(0.0f), 50, 0.0f, s), 0u);

  ShadowPhotonMap shadowEmpty;
  shadowEmpty.build({}, 2);
  EXPECT_EQ(shadowEmpty.size(), 0u);
  EXPECT_FALSE(shadowEmpty.hasPhotons(0));
  EXPECT_EQ(shadowEmpty.knn(Vec3(0.0f), 1, 50, 0.0f, s), 0u);
  EXPECT_EQ(shadowEmpty.knn(Vec3(0.0f), 7, 50, 0.0f, s), 0u);  // no such light
}

TEST(Knn, ShadowMapPartitionsByLightAndSearchesOneLight) {
  Rng rng(5);
  std::vector<ShadowPhoton> in;
  for (uint32_t i = 0; i < 9000; ++i) {
    ShadowPhoton ph{};
    ph.position = Vec3(rng.uniform(), rng.uniform(), 0.0f);
    ph.normal = encodeOctahedral(Vec3(0, 0, 1));
    ph.light = static_cast<uint16_t>(i % 3);
    ph.shadow = (i / 3) % 2;
    in.push_back(ph);
  }
  in.push_back(in[0]);
  in.back().light = 9;  // light index out of range: dropped
  ShadowPhotonMap map;
  map.build(in, 3);
  EXPECT_EQ(map.size(), 9000u);
  EXPECT_GT(map.memoryBytes(), 9000 * sizeof(ShadowPhoton));
  for (uint32_t light = 0; light < 3; ++light) {
    ASSERT_EQ(map.photons(light).size(), 3000u);
    for (const ShadowPhoton& ph : map.photons(light)) ASSERT_EQ(ph.light, light);
    std::vector<IndirectPhoton> asIndirect;  // reuse the brute-force helper
    for (const ShadowPhoton& ph : map.photons(light)) asIndirect.push_back(indirectAt(ph.position));
    Vec3 q(0.3f, 0.6f, 0.01f);
    GatherScratch s;
    size_t n = map.knn(q, light, 50, 0.0f, s);
    Brute b = bruteKnn(asIndirect, q, 50, 0.0f);
    ASSERT_EQ(n, 50u);
    EXPECT_EQ(std::vector<float>(s.dist2.begin(), s.dist2.begin() + n), b.d2);
  }
}

TEST(Knn, DeterministicStructureAtAnyThreadCount) {
  auto cloud = randomCloud(20000, 11);
  // Duplicate positions so the Morton sort has ties to break by original index.
  for (int i = 0; i < 2000; ++i) cloud[10000 + i].position = cloud[i].position;
  for (int i = 0; i < 2000; ++i) cloud[10000 + i].power = Color(2.0f);
  IndirectPhotonMap a, b;
  {
    tbb::global_control one(tbb::global_control::max_allowed_parallelism, 1);
    a.build(cloud);
  }
  b.build(cloud);  // all cores
  ASSERT_EQ(a.size(), b.size());
  for (size_t i = 0; i < a.size(); ++i) {
    ASSERT_EQ(a.photons()[i].position, b.photons()[i].position);
    ASSERT_EQ(a.photons()[i].power, b.photons()[i].power);  // tie order is stable
  }
  GatherScratch sa, sb;
  size_t na = a.knn(Vec3(0.1f), 50, 0.0f, sa), nb = b.knn(Vec3(0.1f), 50, 0.0f, sb);
  ASSERT_EQ(na, nb);
  for (size_t i = 0; i < na; ++i) EXPECT_EQ(sa.indices[i], sb.indices[i]);
}

// ---- exact (dist2, index) answers, with and without search hints -------------------

// The answer is defined as the k smallest (dist2, index) pairs, ascending: compare
// both arrays exactly, ties included.
template <class Map>
void expectExactKnn(const Map& map, const std::vector<IndirectPhoton>& photons, const Vec3& q,
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
  std::vector<IndirectPhoton> cloud;
};
std::vector<HintCase> hintCases() {
  std::vector<HintCase> cases;
  cases.push_back({"random", randomCloud(6000, 21)});
  std::vector<IndirectPhoton> same(400, indirectAt(Vec3(0.1f, 0.2f, 0.3f)));
  for (int i = 0; i < 300; ++i) same.push_back(indirectAt(Vec3(-0.5f, 0.5f, 0.0f)));
  cases.push_back({"identical", same});
  std::vector<IndirectPhoton> line;  // equal spacing: many exactly tied distances
  for (int i = 0; i < 3000; ++i) line.push_back(indirectAt(Vec3(-1.0f + 0.001f * i, 0.25f, 0.0f)));
  cases.push_back({"collinear", line});
  std::vector<IndirectPhoton> grid;  // a lattice: ties at every shell
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
  std::vector<ShadowPhoton> in;
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
  std::vector<ShadowPhoton> shadow;
  std::vector<IndirectPhoton> indirect;
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

TEST(Morton, CodesInterleaveAndDegenerateBoxesAreFinite) {
  EXPECT_EQ(spreadBits21(0b111u), 0b1001001ull);
  EXPECT_EQ(spreadBits21(0x1FFFFFu), 0x1249249249249249ull);
  Bounds b;
  b.extend(Vec3(0.0f));
  b.extend(Vec3(1.0f));
  EXPECT_EQ(mortonCode63(Vec3(0.0f), b), 0u);
  EXPECT_EQ(mortonCode63(Vec3(1.0f), b), 0x7FFFFFFFFFFFFFFFull);
  EXPECT_EQ(mortonCode63(Vec3(1.0f, 0.0f, 0.0f), b), 0x1249249249249249ull);
  Bounds flat;  // a single point: zero extent on every axis
  flat.extend(Vec3(2.0f));
  EXPECT_EQ(mortonCode63(Vec3(2.0f), flat), 0u);
}

}  // namespace
}  // namespace penumbra
