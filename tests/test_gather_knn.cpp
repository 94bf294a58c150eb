// The photon maps' kNN against a brute-force linear scan, including degenerate sets.
#include "gather/morton.h"
#include "gather/photon_map.h"
#include "support/brute_knn.h"
#include <gtest/gtest.h>
#include <tbb/global_control.h>
#include <algorithm>
#include <array>
#include <cmath>
#include <set>

namespace penumbra {
namespace {

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
INSTANTIATE_TEST_SUITE_P(MortonOnOff, KnnRandom, ::testing::Bool(),
                         [](const ::testing::TestParamInfo<bool>& tp) {
                           return std::string(tp.param ? "morton" : "no_morton");
                         });

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
  PhotonArray<IndirectPhoton> same(500, indirectAt(Vec3(0.25f, -1.0f, 3.0f)));
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
  PhotonArray<IndirectPhoton> line;
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
  PhotonArray<ShadowPhoton> in;
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
    PhotonArray<IndirectPhoton> asIndirect;  // reuse the brute-force helper
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
