// The volume map's beam estimate: equal to a brute-force sum over every photon, the
// analytic in-scattered radiance of a uniform isotropic photon cloud, its radius rule,
// and a beam in one medium reading none of another's photons.
#include "core/media/density_grid.h"
#include "core/media/phase_function.h"
#include "core/rng.h"
#include "gather/kd_tree.h"
#include "gather/volume_estimate.h"
#include <glm/gtc/matrix_transform.hpp>
#include <gtest/gtest.h>
#include <cmath>
#include <memory>

namespace penumbra {
namespace {

// n photons uniform in [0, side]^3, random directions, power `power` each (random
// colours when `colours`), medium `medium`.
PhotonArray<VolumePhoton> cloud(size_t n, float side, float power, bool colours, uint64_t seed, int medium = 0) {
  Rng rng(seed);
  PhotonArray<VolumePhoton> out(n);
  for (VolumePhoton& p : out) {
    p.position = Vec3(rng.uniform(), rng.uniform(), rng.uniform()) * side;
    const float z = 1.0f - 2.0f * rng.uniform(), phi = 2.0f * kPi * rng.uniform();
    const float s = std::sqrt(std::max(0.0f, 1.0f - z * z));
    p.direction = encodeOctahedral(Vec3(s * std::cos(phi), s * std::sin(phi), z));
    p.power = colours ? Color(rng.uniform(), rng.uniform(), rng.uniform()) * power : Color(power);
    p.medium = medium;
  }
  return out;
}

Medium medium(Color sigmaT, float g) {
  Medium m;
  m.sigmaA = sigmaT * 0.25f;
  m.sigmaS = sigmaT * 0.75f;
  m.g = g;
  return m;
}

// The estimate's formula over all photons, with the same decoded records.
VolumeEstimate bruteForce(const PhotonArray<VolumePhoton>& photons, const VolumeQuery& q, const Medium& m, float r) {
  VolumeEstimate e;
  for (const VolumePhoton& p : photons) {
    const Vec3 v = p.position - q.origin;
    const float t = glm::dot(v, q.dir);
    if (t < q.tMin || t > q.tMax || glm::dot(v, v) - t * t >= r * r) continue;
    if (q.medium != kNoMedium && p.medium != q.medium) continue;
    const float phase = henyeyGreenstein(m.g, -glm::dot(decodeOctahedral(p.direction), q.dir));
    e.value += glm::exp(-m.sigmaT() * (t - q.tMin)) * phase * p.power.color();
    ++e.found;
  }
  e.value /= kPi * r * r;
  return e;
}

TEST(GatherVolume, BeamEqualsBruteForce) {
  PhotonArray<VolumePhoton> photons = cloud(20000, 2.0f, 1e-3f, true, 5);
  const PhotonArray<VolumePhoton> copy = photons;
  VolumePhotonMap map;
  map.build(PhotonBatches<VolumePhoton>(std::move(photons)));
  ASSERT_EQ(map.size(), copy.size());
  GatherScratch scratch;
  Rng rng(99);
  int compared = 0;
  for (const Medium& m : {medium(Color(0.4f, 0.8f, 1.6f), 0.7f), medium(Color(0.5f), 0.0f)}) {
    for (int i = 0; i < 300; ++i) {
      VolumeQuery q;
      // Origins inside and outside the cloud, every direction, axis-aligned ones too.
      q.origin = Vec3(rng.uniform(), rng.uniform(), rng.uniform()) * 4.0f - 1.0f;
      Vec3 d = Vec3(rng.uniform(), rng.uniform(), rng.uniform()) * 2.0f - q.origin;  // at a point of the cloud
      if (i % 10 == 0) d = Vec3(0.0f, 0.0f, 0.0f), d[i / 10 % 3] = i % 20 == 0 ? 1.0f : -1.0f;
      q.dir = glm::normalize(d);
      q.tMin = rng.uniform();
      q.tMax = q.tMin + 4.0f * rng.uniform();
      const float r = 0.02f + 0.2f * rng.uniform();
      const VolumeEstimate got = volumeRadiance(map, q, m, 0, r, scratch);
      const VolumeEstimate want = bruteForce(copy, q, m, r);
      ASSERT_EQ(got.found, want.found) << "query " << i;
      for (int c = 0; c < 3; ++c) ASSERT_NEAR(got.value[c], want.value[c], 1e-4f * want.value[c] + 1e-9f);
      compared += want.found > 0;
    }
  }
  EXPECT_GT(compared, 400);
}

// Photons of power Phi at n per unit volume, isotropic phase: the beam over [0, L]
// expects n Phi / (4 pi) integral_0^L T(t) dt, T = exp(-sigma_t t).
TEST(GatherVolume, UniformIsotropicCloudGivesTheAnalyticInScatter) {
  const size_t n = 400000;
  const float power = 1.0f / n;  // n photons per unit volume of [0, 1]^3
  VolumePhotonMap map;
  map.build(PhotonBatches<VolumePhoton>(cloud(n, 1.0f, power, false, 17)));
  GatherScratch scratch;
  for (float sigmaT : {0.0f, 2.0f}) {
    const Medium m = medium(Color(sigmaT), 0.0f);
    const float length = 0.8f, r = 0.05f;
    const double integral = sigmaT > 0.0f ? (1.0 - std::exp(-sigmaT * length)) / sigmaT : length;
    const double want = double(n) * power / (4.0 * kPi) * integral;
    double sum = 0.0;
    int beams = 0;
    for (float x = 0.2f; x < 0.81f; x += 0.15f) {
      for (float y = 0.2f; y < 0.81f; y += 0.15f, ++beams) {
        VolumeQuery q{Vec3(x, y, 0.1f), Vec3(0.0f, 0.0f, 1.0f), 0.0f, length};
        sum += volumeRadiance(map, q, m, 0, r, scratch).value.g;
      }
    }
    // ~1000 photons per beam, 25 beams: ~0.6% noise.
    EXPECT_NEAR(sum / beams, want, 0.025 * want) << "sigma_t " << sigmaT;
  }
  // The radius rule: a unit cube's mean chord 2/3, so k = n pi r^2 2/3.
  EXPECT_NEAR(map.radiusFor(100), std::sqrt(100.0 / (kPi * n * 2.0 / 3.0)), 0.01 * map.radiusFor(100));
  VolumeQuery q{Vec3(0.5f, 0.5f, 0.0f), Vec3(0.0f, 0.0f, 1.0f), 0.0f, 2.0f / 3.0f};
  const VolumeEstimate e = volumeRadiance(map, q, medium(Color(0.0f), 0.0f), 100, 0.0f, scratch);
  EXPECT_GT(e.found, 60u);
  EXPECT_LT(e.found, 150u);
}

TEST(GatherVolume, ConstantGridMatchesHomogeneousAndMediaStayApart) {
  PhotonArray<VolumePhoton> a = cloud(20000, 1.0f, 1e-3f, false, 3, 0);
  const PhotonArray<VolumePhoton> b = cloud(20000, 1.0f, 1e-3f, false, 4, 1);
  a.insert(a.end(), b.begin(), b.end());
  VolumePhotonMap map;
  map.build(PhotonBatches<VolumePhoton>(std::move(a)));
  GatherScratch scratch;
  Medium plain = medium(Color(1.5f), 0.4f), gridded = plain;
  auto grid = std::make_shared<DensityGrid>();
  grid->nx = grid->ny = grid->nz = 4;
  grid->values.assign(64, 1.0f);
  grid->maxDensity = 1.0f;
  grid->worldToGrid = glm::scale(glm::mat4(1.0f), Vec3(4.0f));  // voxel centres over [0, 1]: dense inside
  grid->worldToGrid = glm::translate(glm::mat4(1.0f), Vec3(-0.5f)) * grid->worldToGrid;
  grid->worldLo = Vec3(-1.0f);
  grid->worldHi = Vec3(2.0f);
  gridded.density = grid;
  VolumeQuery q{Vec3(0.5f, 0.5f, 0.2f), glm::normalize(Vec3(0.1f, 0.05f, 1.0f)), 0.0f, 0.6f, 0};
  const VolumeEstimate h = volumeRadiance(map, q, plain, 0, 0.1f, scratch);
  const VolumeEstimate g = volumeRadiance(map, q, gridded, 0, 0.1f, scratch);
  ASSERT_GT(h.found, 50u);
  EXPECT_EQ(h.found, g.found);
  EXPECT_NEAR(g.value.r, h.value.r, 2e-3f * h.value.r);
  // Medium 0's beam reads half the photons the medium-blind beam does.
  q.medium = kNoMedium;
  const VolumeEstimate all = volumeRadiance(map, q, plain, 0, 0.1f, scratch);
  EXPECT_NEAR(double(all.found), 2.0 * h.found, 6.0 * std::sqrt(double(h.found)));
}

}  // namespace
}  // namespace penumbra
