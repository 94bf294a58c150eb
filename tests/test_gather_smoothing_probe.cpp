// The gathers' smoothing probe (RadianceEstimate::smoothing) against the bias it
// estimates, measured by brute force: photons drawn from a known flux density, the
// estimate's mean over many maps less the density at the query.
#include "core/bsdf.h"
#include "core/rng.h"
#include "gather/photon_map.h"
#include "gather/radiance_estimate.h"
#include "support/cache_photons.h"
#include <gtest/gtest.h>
#include <cmath>

namespace penumbra {
namespace {

const Vec3 kUp(0, 0, 1);

// n photons of power 1 / n over the unit square at z = 0: a share `bump` of them from a
// Gaussian of deviation `sigma` at the centre, the rest uniform; `irradiance` is their
// flux density.
struct BumpPlane {
  double bump = 0.5, sigma = 0.03;
  double irradiance(double x, double y) const {
    const double r2 = (x - 0.5) * (x - 0.5) + (y - 0.5) * (y - 0.5);
    return (1.0 - bump) + bump * std::exp(-r2 / (2 * sigma * sigma)) / (2 * kPi * sigma * sigma);
  }
  IndirectPhotonMap map(int n, uint64_t seed) const {
    PhotonArray<IndirectPhoton> out;
    Rng rng(seed);
    for (int i = 0; i < n; ++i) {
      Vec3 p(rng.uniform(), rng.uniform(), 0.0f);
      if (rng.uniform() < bump) {  // Box-Muller
        const double u = std::max(1e-12, double(rng.uniform())), v = rng.uniform();
        const double r = sigma * std::sqrt(-2.0 * std::log(u));
        p = Vec3(float(0.5 + r * std::cos(2 * kPi * v)), float(0.5 + r * std::sin(2 * kPi * v)), 0.0f);
      }
      out.push_back(testing::planePhoton(p, kUp, Color(1.0f / n)));
    }
    IndirectPhotonMap m;
    m.build(std::move(out));
    return m;
  }
};

// Over `maps` maps, the mean of the estimate's error against the density's radiance,
// and the mean of its smoothing probe, at points within a third of sigma of the bump's
// peak (where its curvature is nearly constant), as shares of the radiance there.
struct Means {
  double bias = 0.0, probe = 0.0;
};
Means bumpMeans(const BumpPlane& plane, int photons, int k, int maps) {
  const BsdfFrame frame{kUp, kUp, true};
  GatherScratch s;
  Means m;
  int count = 0;
  for (int seed = 0; seed < maps; ++seed) {
    const IndirectPhotonMap map = plane.map(photons, 1000 + seed);
    for (int j = -2; j <= 2; ++j)
      for (int i = -2; i <= 2; ++i) {
        const double x = 0.5 + i * plane.sigma / 6, y = 0.5 + j * plane.sigma / 6;
        const double truth = plane.irradiance(x, y) / kPi;
        const RadianceEstimate e = photonRadiance(map, testing::whiteLambertian(), frame, Vec3(float(x), float(y), 0.0f), kUp,
                                                  PhotonGather{k, 0.0f, true}, s);
        m.bias += (e.value.x - truth) / truth;
        m.probe += e.smoothing.x / truth;
        ++count;
      }
  }
  m.bias /= count;
  m.probe /= count;
  return m;
}

// At a peak the kernel flattens the estimate: a bias of a few percent that the probe,
// from the same photons, reads within a fifth of it (the means' noise is about 0.2%).
TEST(SmoothingProbe, ReadsTheBiasAtAPeakMeasuredByBruteForce) {
  const Means m = bumpMeans(BumpPlane{}, 5000, 200, 1000);
  EXPECT_LT(m.bias, -0.02);  // the test would say nothing about a bias lost in noise
  EXPECT_NEAR(m.probe / m.bias, 1.0, 0.2) << "bias " << m.bias << ", probe " << m.probe;
}

// On a uniform density the estimate has no bias (k-nearest, its k-th photon weighs 0),
// and the probe averages to 0 within its noise.
// Its 25 points share their photons: the means' noise is about a single estimate's (7%
// at k 200) over the root of the maps, 0.16%.
TEST(SmoothingProbe, AveragesToZeroOnAUniformDensity) {
  const Means m = bumpMeans(BumpPlane{0.0, 0.03}, 5000, 200, 2000);
  EXPECT_NEAR(m.bias, 0.0, 0.006);
  EXPECT_NEAR(m.probe, 0.0, 0.006);
}

// Asking for the probe leaves the estimate itself unchanged, bit for bit.
TEST(SmoothingProbe, LeavesTheEstimateUnchanged) {
  const IndirectPhotonMap map = BumpPlane{}.map(5000, 7);
  const BsdfFrame frame{kUp, kUp, true};
  GatherScratch s;
  for (int i = 0; i < 50; ++i) {
    const Vec3 p(0.3f + 0.008f * i, 0.5f, 0.0f);
    const RadianceEstimate plain = photonRadiance(map, testing::whiteLambertian(), frame, p, kUp, PhotonGather{100, 0.0f}, s);
    const RadianceEstimate probed = photonRadiance(map, testing::whiteLambertian(), frame, p, kUp, PhotonGather{100, 0.0f, true}, s);
    EXPECT_EQ(plain.value, probed.value);
    EXPECT_EQ(plain.smoothing, Color(0.0f));
  }
}

}  // namespace
}  // namespace penumbra
