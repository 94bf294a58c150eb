// Statistics of sampleCollision and mediumTransmittance for the media tests: where
// collisions land (a histogram for chi-squared against a CDF) and the mean of each
// channel's weight with and without a collision, with standard errors.
#pragma once
#include "core/media/tracking.h"
#include "support/chi2.h"
#include <array>
#include <cmath>
#include <functional>
#include <vector>

namespace penumbra::testing {

inline Medium makeMedium(const Color& sigmaA, const Color& sigmaS, float g = 0.0f) {
  Medium m;
  m.name = "test";
  m.sigmaA = sigmaA;
  m.sigmaS = sigmaS;
  m.g = g;
  return m;
}

// A sample mean and its standard error.
struct Mean {
  double sum = 0.0, sumSq = 0.0;
  int n = 0;
  void add(double v) { sum += v, sumSq += v * v, ++n; }
  double mean() const { return sum / n; }
  double stdError() const { return std::sqrt(std::max(0.0, sumSq / n - mean() * mean()) / n); }
};

struct CollisionStats {
  std::vector<double> bins;          // collisions by distance from a, over [a, b) in equal bins
  double none = 0.0;                 // flights that reached b
  std::array<Mean, 3> weightNone;    // per channel: weight x [no collision]
  std::array<Mean, 3> weightHit;     // per channel: weight x [collision]
  bool finite = true;                // every weight finite and >= 0, every t in [a, b]
  double maxWeight = 0.0;
};

// n flights over [a, b] of o + t d; `span` is the histogram's length (b - a, or a
// cut-off for an infinite b, beyond which collisions land in the last bin).
inline CollisionStats collisions(const Medium& m, const Vec3& o, const Vec3& d, float a, float b, int n,
                                 uint64_t seed, int binCount, float span) {
  CollisionStats s;
  s.bins.assign(binCount, 0.0);
  Rng rng(seed);
  for (int k = 0; k < n; ++k) {
    const MediumCollision c = sampleCollision(m, o, d, a, b, rng);
    for (int ch = 0; ch < 3; ++ch) {
      const double w = c.weight[ch];
      if (!(std::isfinite(w) && w >= 0.0)) s.finite = false;
      s.maxWeight = std::max(s.maxWeight, w);
      s.weightNone[ch].add(c.collided ? 0.0 : w);
      s.weightHit[ch].add(c.collided ? w : 0.0);
    }
    if (!c.collided) {
      s.none += 1.0;
      if (c.t != b) s.finite = false;
      continue;
    }
    if (!(c.t >= a && c.t <= b)) s.finite = false;
    const int i = std::clamp(int((c.t - a) / span * binCount), 0, binCount - 1);
    s.bins[i] += 1.0;
  }
  return s;
}

// P(a collision before x) in a homogeneous medium with RGB sigmaT: sampleCollision
// draws each channel's exponential with probability 1/3 (its hero channel).
inline double heroMixtureCdf(const Color& sigmaT, double x) {
  double p = 0.0;
  for (int c = 0; c < 3; ++c) p += (1.0 - std::exp(-double(sigmaT[c]) * x)) / 3.0;
  return p;
}

// Chi-squared of the histogram plus the no-collision cell against cdf(x) = P(a
// collision before a + x); the last bin takes everything past `span`.
inline chi2::Result collisionChi2(const CollisionStats& s, const std::function<double(double)>& cdf, float span,
                                  double pNone) {
  const int binCount = int(s.bins.size());
  std::vector<double> observed = s.bins, expected(binCount + 1);
  observed.push_back(s.none);
  double n = 0.0;
  for (double o : observed) n += o;
  for (int i = 0; i < binCount; ++i) {
    const double hi = i + 1 == binCount ? 1.0 - pNone : cdf(double(span) * (i + 1) / binCount);
    expected[i] = n * (hi - cdf(double(span) * i / binCount));
  }
  expected[binCount] = n * pNone;
  return chi2::test(observed, expected, n);
}

}  // namespace penumbra::testing
