// Maps big enough to be split into parts (Morton ranges built side by side): the
// k nearest and the radius search over all parts against a brute-force scan, and
// the same storage order and answers at any thread count.
#include "gather/kd_tree.h"
#include "gather/photon_map.h"
#include "support/brute_knn.h"
#include <gtest/gtest.h>
#include <tbb/blocked_range.h>
#include <tbb/global_control.h>
#include <tbb/parallel_for.h>
#include <tbb/task_group.h>
#include <algorithm>

namespace penumbra {
namespace {

// 700k photons: three parts of ~256k. Half in a unit cube, half on two distant planes,
// so parts have very different boxes and queries between them must visit several.
PhotonArray<IndirectPhoton> partedCloud() {
  PhotonArray<IndirectPhoton> cloud = randomCloud(350000, 21);
  Rng rng(22);
  for (int i = 0; i < 350000; ++i) {
    const float side = i % 2 ? 3.0f : -3.0f;
    cloud.push_back(indirectAt(Vec3(rng.uniform() * 2 - 1, side, rng.uniform() * 2 - 1)));
  }
  return cloud;
}

TEST(KnnParts, MatchesBruteForceAcrossParts) {
  IndirectPhotonMap map;
  map.build(partedCloud());
  ASSERT_EQ(map.size(), 700000u);
  const auto& photons = map.photons();
  Rng rng(5);
  for (int qi = 0; qi < 10; ++qi) {
    // In the cube, between the cube and a plane (both at similar distance), far outside.
    const Vec3 q = qi < 4   ? Vec3(rng.uniform(), rng.uniform(), rng.uniform()) * 2.0f - 1.0f
                   : qi < 8 ? Vec3(rng.uniform() - 0.5f, 2.0f, rng.uniform() - 0.5f)
                            : Vec3(0.0f, 0.0f, 40.0f);
    for (size_t k : {1, 50, 200})
      for (float r : {0.0f, 0.03f, 1.5f}) expectMatchesBrute(map, photons, q, k, r);
  }
}

TEST(KnnParts, RadiusSearchFindsEveryPhotonOnce) {
  IndirectPhotonMap map;
  map.build(partedCloud());
  const auto& photons = map.photons();
  GatherScratch s;
  for (const Vec3& q : {Vec3(0.0f, 1.02f, 0.0f), Vec3(0.5f, 2.5f, 0.5f), Vec3(0.1f)}) {
    const float r = 1.3f;
    size_t n = map.within(q, r, s);
    std::vector<uint32_t> got(s.indices.begin(), s.indices.begin() + n), want;
    for (uint32_t i = 0; i < photons.size(); ++i)
      if (dist2(photons[i].position, q) < r * r) want.push_back(i);
    std::sort(got.begin(), got.end());
    EXPECT_EQ(got, want);
    EXPECT_GT(want.size(), 1000u);
  }
}

TEST(KnnParts, SameOrderAndAnswersAtAnyThreadCount) {
  IndirectPhotonMap a, b;
  {
    tbb::global_control one(tbb::global_control::max_allowed_parallelism, 1);
    a.build(partedCloud());
  }
  b.build(partedCloud());
  ASSERT_EQ(a.size(), b.size());
  for (size_t i = 0; i < a.size(); ++i) ASSERT_EQ(a.photons()[i].position, b.photons()[i].position);
  GatherScratch sa, sb;
  for (const Vec3& q : {Vec3(0.3f), Vec3(0.0f, 3.0f, 0.0f)}) {
    size_t na = a.knn(q, 100, 0.0f, sa), nb = b.knn(q, 100, 0.0f, sb);
    ASSERT_EQ(na, nb);
    for (size_t i = 0; i < na; ++i) EXPECT_EQ(sa.indices[i], sb.indices[i]);
  }
}

// An exception elsewhere in an enclosing parallel algorithm (another light's tree or
// another map running out of memory) cancels the parts not yet built: the tree stays
// empty, and the exception propagates from there, instead of reading parts it never built.
TEST(KnnParts, CancelledBuildStaysEmpty) {
  PhotonArray<IndirectPhoton> cloud = partedCloud();
  PhotonKdTree<IndirectPhoton> tree;
  tbb::task_group_context group;
  tbb::parallel_for(
      tbb::blocked_range<int>(0, 1),
      [&](const tbb::blocked_range<int>&) {
        group.cancel_group_execution();
        tree.build(cloud.data(), cloud.size(), 48, false, nullptr);
      },
      group);
  GatherScratch scratch;
  EXPECT_EQ(tree.knn(Vec3(0.3f), 10, 0.0f, scratch), 0u);
}

}  // namespace
}  // namespace penumbra
