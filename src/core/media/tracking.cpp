// Transmittance and collisions in one medium (core/media/tracking.h): closed forms in a
// homogeneous medium, ratio and delta tracking against the grid's majorant otherwise.
#include "core/media/tracking.h"
#include "core/media/density_grid.h"
#include "core/media/homogeneous.h"
#include <algorithm>
#include <array>
#include <cmath>

namespace penumbra {

Color sigmaSAt(const Medium& m, const Vec3& p) { return m.density ? m.sigmaS * m.density->at(p) : m.sigmaS; }
Color sigmaTAt(const Medium& m, const Vec3& p) { return m.density ? m.sigmaT() * m.density->at(p) : m.sigmaT(); }
Color emissionAt(const Medium& m, const Vec3& p) {
  return m.density ? m.sigmaA * m.emission * m.density->at(p) : m.sigmaA * m.emission;
}

namespace {

using Rgb = std::array<double, 3>;

// A safety net, not a tuning knob: tracking takes about majorant x length steps, so a
// grid scaled to sigma ~ 1e30 would never finish. Past this many steps the segment is
// treated as opaque (optical depths this large transmit nothing a float can hold).
constexpr int kMaxTrackingSteps = 1 << 16;
// Ratio tracking plays Russian roulette once every channel's estimate is below this.
constexpr double kRouletteBelow = 0.1;

Rgb rgb(const Color& c) { return {c.r, c.g, c.b}; }
Color color(const Rgb& c) { return Color(float(c[0]), float(c[1]), float(c[2])); }
double mean(const Rgb& c) { return (c[0] + c[1] + c[2]) / 3.0; }

// The grid's majorant: a density bound times the largest channel of sigmaT, so every
// channel's null coefficient (majorant - sigmaT(x)) is >= 0.
double majorant(const Medium& m) { return double(m.density->maxDensity) * maxComponent(m.sigmaT()); }

int heroChannel(Rng& rng) { return std::min(int(rng.uniform() * 3.0f), 2); }

// Homogeneous: a free flight drawn by one channel's sigmaT chosen uniformly (the hero),
// weighted by the balance heuristic over the three channels' densities (one-sample MIS):
// each weight is at most 3 x the albedo, and exactly albedo / 1 for a grey medium.
MediumCollision homogeneousCollision(const Medium& m, float a, float b, Rng& rng) {
  const Rgb st = rgb(m.sigmaT()), ss = rgb(m.sigmaS);
  const int h = heroChannel(rng);
  const double d = double(b) - double(a);  // inf for an infinite medium
  const float u = rng.uniform();
  const double x = st[h] > 0.0 ? freeFlightDistance(st[h], u) : kInf;
  if (x >= d) {
    // The hero's P(none) >= exp(-16.6) here, so the mean never vanishes.
    Rgb p;
    for (int c = 0; c < 3; ++c) p[c] = opticalExp(st[c], d);
    const double norm = mean(p);
    return {false, b, color({p[0] / norm, p[1] / norm, p[2] / norm})};
  }
  Rgb pdf, f;
  for (int c = 0; c < 3; ++c) {
    const double tr = opticalExp(st[c], x);
    pdf[c] = st[c] * tr;
    f[c] = ss[c] * tr;
  }
  const double norm = mean(pdf);  // >= sigma_h exp(-16.6) / 3 > 0
  const float t = std::clamp(float(double(a) + x), a, b);
  return {true, t, color({f[0] / norm, f[1] / norm, f[2] / norm})};
}

// The tentative collisions along [a, b] in a grid: free flights against each block's
// majorant (memoryless, so a flight past a block's end restarts at the boundary with
// the next bound), calling event(t, density, majorant) until it returns false.
enum class TrackEnd { Reached, Stopped, Opaque };
template <class Event>
TrackEnd trackEvents(const Medium& m, const Vec3& o, const Vec3& d, float a, float b, Rng& rng, double& t,
                     Event&& event) {
  const double channelMax = maxComponent(m.sigmaT());
  MajorantWalk walk(*m.density, o, d, a, b);
  double t0, t1;
  float bound;
  int steps = 0;
  while (walk.next(t0, t1, bound)) {
    const double mu = double(bound) * channelMax;
    if (!(mu > 0.0)) continue;  // an empty block: nothing to meet
    for (t = t0;;) {
      if (++steps > kMaxTrackingSteps) return TrackEnd::Opaque;
      t += freeFlightDistance(mu, rng.uniform());
      if (t >= t1) break;
      if (!event(t, double(m.density->at(o + float(t) * d)), mu)) return TrackEnd::Stopped;
    }
  }
  return TrackEnd::Reached;
}

// Grid: delta tracking with the same one-sample MIS over the channels: the hero
// accepts a real collision with probability sigmaT_h(x) / majorant; f is the channels'
// contribution over the hero's path density, r each channel's path density over the
// hero's, and the weight f / mean(r) stays unbiased per channel.
MediumCollision gridCollision(const Medium& m, const Vec3& o, const Vec3& d, float a, float b, Rng& rng) {
  const Rgb st = rgb(m.sigmaT()), ss = rgb(m.sigmaS);
  const int h = heroChannel(rng);
  Rgb f{1.0, 1.0, 1.0}, r{1.0, 1.0, 1.0}, w{0.0, 0.0, 0.0};
  double t = a;
  const TrackEnd end = trackEvents(m, o, d, a, b, rng, t, [&](double, double rho, double mu) {
    Rgb p;  // each channel's real-collision probability
    for (int c = 0; c < 3; ++c) p[c] = std::clamp(rho * st[c] / mu, 0.0, 1.0);
    if (rng.uniform() < p[h]) {
      // The real collision's event: f_c *= (rho sigmaS_c / majorant) / p_h and
      // r_k *= p_k / p_h; the p_h cancels in f / mean(r). r_h = 1, so the sum >= p_h.
      const double norm = (r[0] * p[0] + r[1] * p[1] + r[2] * p[2]) / 3.0;
      for (int c = 0; c < 3; ++c) w[c] = f[c] * rho * ss[c] / mu / norm;
      return false;
    }
    const double q = 1.0 - p[h];  // > 0: a null collision was drawn
    double rMax = 0.0;
    for (int c = 0; c < 3; ++c) {
      f[c] *= (1.0 - p[c]) / q;  // sigma_n,c / majorant = 1 - p_c
      r[c] *= (1.0 - p[c]) / q;
      rMax = std::max(rMax, r[c]);
    }
    // Both f and r are ratios to the hero's density; rescaling them together keeps
    // f / mean(r) and keeps either from overflowing over many null collisions.
    if (rMax > 1e100) {
      for (int c = 0; c < 3; ++c) f[c] /= rMax, r[c] /= rMax;
    }
    return true;
  });
  if (end == TrackEnd::Stopped) return {true, float(t), color(w)};
  if (end == TrackEnd::Opaque) return {true, float(t), Color(0.0f)};  // absorbed
  const double norm = mean(r);
  return {false, b, color({f[0] / norm, f[1] / norm, f[2] / norm})};
}

// Grid: ratio tracking (Novák et al. 2014) over the same blocks; each channel's
// estimate is the product of its null fractions, 1 - sigmaT_c(x) / majorant.
Color gridTransmittance(const Medium& m, const Vec3& o, const Vec3& d, float a, float b, Rng& rng) {
  const Rgb st = rgb(m.sigmaT());
  Rgb tr{1.0, 1.0, 1.0};
  double t = a;
  const TrackEnd end = trackEvents(m, o, d, a, b, rng, t, [&](double, double rho, double mu) {
    for (int c = 0; c < 3; ++c) tr[c] *= std::max(0.0, 1.0 - rho * st[c] / mu);
    const double tMax = std::max(tr[0], std::max(tr[1], tr[2]));
    if (!(tMax > 0.0)) return false;
    if (tMax < kRouletteBelow) {
      // Survive with probability tMax / kRouletteBelow: the survivors' estimate is
      // divided by it, so the mean is kept and thick media stop early.
      const double survive = tMax / kRouletteBelow;
      if (rng.uniform() >= survive) return false;
      for (double& c : tr) c /= survive;
    }
    return true;
  });
  return end == TrackEnd::Reached ? color(tr) : Color(0.0f);
}

}  // namespace

float mediumMajorant(const Medium& m) {
  return m.homogeneous() ? maxComponent(m.sigmaT()) : float(majorant(m));
}

Color mediumTransmittance(const Medium& m, const Vec3& o, const Vec3& d, float a, float b, Rng& rng) {
  if (!(b > a)) return Color(1.0f);
  if (m.homogeneous()) return transmittance(m.sigmaT(), b - a);
  return gridTransmittance(m, o, d, a, b, rng);
}

MediumCollision sampleCollision(const Medium& m, const Vec3& o, const Vec3& d, float a, float b, Rng& rng) {
  if (!(b > a)) return {false, b, Color(1.0f)};
  if (m.homogeneous()) return homogeneousCollision(m, a, b, rng);
  return gridCollision(m, o, d, a, b, rng);
}

}  // namespace penumbra
