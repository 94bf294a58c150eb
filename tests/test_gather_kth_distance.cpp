// kthNearestDistances against the KD-tree's k-nearest search it stands in for (the
// cell size's probes): equal to the bit on points in a volume, on a plane, in tight
// clusters far apart, with fewer points than k, and at probes that are not points.
#include "gather/kth_distance.h"
#include "gather/photon_map.h"
#include "core/rng.h"
#include <gtest/gtest.h>
#include <algorithm>
#include <vector>

namespace penumbra {
namespace {

PhotonArray<ShadowPhoton> photonsAt(const std::vector<Vec3>& points) {
  PhotonArray<ShadowPhoton> out;
  for (const Vec3& p : points) {
    ShadowPhoton ph{};
    ph.position = p;
    ph.normal = encodeOctahedral(Vec3(0, 0, 1));
    ph.light = 0;
    out.push_back(ph);
  }
  return out;
}

// The tree's k-th distance at each probe, as cacheCellSize's probes ask it.
std::vector<float> treeDistances(const std::vector<Vec3>& points, const std::vector<Vec3>& probes, size_t k) {
  ShadowPhotonMap map;
  map.build(photonsAt(points), 1);
  GatherScratch s;
  std::vector<float> out;
  for (const Vec3& q : probes) {
    const size_t n = map.knn(q, 0, k, 0.0f, s);
    float r2 = 0.0f;
    for (size_t j = 0; j < n; ++j) r2 = std::max(r2, s.dist2[j]);
    out.push_back(std::sqrt(r2));
  }
  return out;
}

void expectSameAsTree(const std::vector<Vec3>& points, const std::vector<Vec3>& probes, size_t k) {
  const PhotonArray<ShadowPhoton> photons = photonsAt(points);
  const std::vector<float> grid = kthNearestDistances(photons.data(), photons.size(), probes, k);
  const std::vector<float> tree = treeDistances(points, probes, k);
  ASSERT_EQ(grid.size(), tree.size());
  for (size_t i = 0; i < grid.size(); ++i) EXPECT_EQ(grid[i], tree[i]) << "probe " << i << " k " << k;
}

std::vector<Vec3> random(size_t n, const Vec3& scale, uint64_t seed) {
  Rng rng(seed);
  std::vector<Vec3> out;
  for (size_t i = 0; i < n; ++i) out.push_back(Vec3(rng.uniform(), rng.uniform(), rng.uniform()) * scale);
  return out;
}

std::vector<Vec3> everyNth(const std::vector<Vec3>& points, size_t step) {
  std::vector<Vec3> out;
  for (size_t i = 0; i < points.size(); i += step) out.push_back(points[i]);
  return out;
}

TEST(KthNearestDistances, EqualsTheTreeInAVolume) {
  const std::vector<Vec3> points = random(20000, Vec3(3.0f, 1.0f, 2.0f), 1);
  for (size_t k : {1, 8, 50}) expectSameAsTree(points, everyNth(points, 97), k);
}

TEST(KthNearestDistances, EqualsTheTreeOnAPlaneAndAtProbesThatAreNotPoints) {
  // A floor: zero extent in y, which the grid must not divide by.
  const std::vector<Vec3> points = random(20000, Vec3(12.0f, 0.0f, 12.0f), 2);
  expectSameAsTree(points, everyNth(points, 101), 50);
  expectSameAsTree(points, random(64, Vec3(12.0f, 0.5f, 12.0f), 3), 50);
}

TEST(KthNearestDistances, EqualsTheTreeForClustersFarApart) {
  // Two dense clusters 1000 apart: the grid's cells are wide, the clusters fine.
  std::vector<Vec3> points = random(5000, Vec3(0.01f), 4);
  for (const Vec3& p : random(5000, Vec3(0.01f), 5)) points.push_back(p + Vec3(1000.0f, 0.0f, 0.0f));
  expectSameAsTree(points, everyNth(points, 50), 50);
}

TEST(KthNearestDistances, FewerPointsThanKGiveTheFarthest) {
  const std::vector<Vec3> points = random(30, Vec3(1.0f), 6);
  expectSameAsTree(points, everyNth(points, 3), 50);
  const std::vector<Vec3> one{Vec3(0.5f)};
  const PhotonArray<ShadowPhoton> photons = photonsAt(one);
  EXPECT_EQ(kthNearestDistances(photons.data(), photons.size(), {Vec3(0.5f, 0.5f, 1.5f)}, 50)[0], 1.0f);
  EXPECT_EQ(kthNearestDistances(photons.data(), 0, {Vec3(0.0f)}, 50)[0], 0.0f);
}

}  // namespace
}  // namespace penumbra
