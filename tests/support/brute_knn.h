// Brute-force k-nearest search and random photon clouds: the reference the
// gather tests hold the KD-tree queries to.
#pragma once
#include "core/rng.h"
#include "gather/photon_map.h"
#include <gtest/gtest.h>
#include <algorithm>
#include <set>
#include <tuple>
#include <vector>

namespace penumbra {

inline IndirectPhoton indirectAt(const Vec3& p) {
  return {p, Color(1.0f), encodeOctahedral(Vec3(0, 0, 1)), encodeOctahedral(Vec3(0, 0, 1))};
}

inline PhotonArray<IndirectPhoton> randomCloud(size_t n, uint64_t seed) {
  Rng rng(seed);
  PhotonArray<IndirectPhoton> out;
  for (size_t i = 0; i < n; ++i)
    out.push_back(indirectAt(Vec3(rng.uniform(), rng.uniform(), rng.uniform()) * 2.0f - 1.0f));
  return out;
}

// Squared distances the same way nanoflann's L2_Simple_Adaptor sums them, so ties and
// the radius cut-off agree to the bit.
inline float dist2(const Vec3& a, const Vec3& b) {
  float s = 0.0f;
  for (int i = 0; i < 3; ++i) s += (a[i] - b[i]) * (a[i] - b[i]);
  return s;
}

struct Brute {
  std::vector<float> d2;          // ascending, k nearest
  std::vector<uint32_t> indices;  // same order
};
template <class Photon>
Brute bruteKnn(const PhotonArray<Photon>& photons, const Vec3& q, size_t k, float maxRadius) {
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
void expectMatchesBrute(const Map& map, const PhotonArray<IndirectPhoton>& photons,
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
        [](const Vec3& l, const Vec3& r) { return std::tie(l.x, l.y, l.z) < std::tie(r.x, r.y, r.z); });
    std::set<Vec3, bool (*)(const Vec3&, const Vec3&)> wantPos(gotPos.key_comp());
    for (uint32_t i : gotIdx) gotPos.insert(photons[i].position);
    for (uint32_t i : b.indices) wantPos.insert(photons[i].position);
    EXPECT_EQ(gotIdx.size(), n);
    EXPECT_EQ(gotPos, wantPos);
  }
}

}  // namespace penumbra
