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

// The part of [a, b] inside the grid's world box (density is 0 outside it).
bool clipToBox(const DensityGrid& g, const Vec3& o, const Vec3& d, float& a, float& b) {
  for (int i = 0; i < 3; ++i) {
    if (d[i] == 0.0f) {
      if (o[i] < g.worldLo[i] || o[i] > g.worldHi[i]) return false;
      continue;
    }
    const float inv = 1.0f / d[i];
    float t0 = (g.worldLo[i] - o[i]) * inv, t1 = (g.worldHi[i] - o[i]) * inv;
    if (t0 > t1) std::swap(t0, t1);
    a = std::max(a, t0);
    b = std::min(b, t1);
  }
  return a < b;
}

// The grid's majorant: the largest density times the largest channel of sigmaT, so
// every channel's null coefficient (majorant - sigmaT(x)) is >= 0.
double majorant(const Medium& m) { return double(m.density->maxDensity) * maxComponent(m.sigmaT()); }

int heroChannel(Rng& rng) { return std::min(int(rng.uniform() * 3.0f), 2); }

// Homogeneous: a free flight drawn by one channel's sigmaT chosen uniformly (the hero),
// weighted by the balance heuristic over the three channels' densities (one-sample MIS):
// each weight is at most 3 x the albedo, and exactly albedo / 1 for a grey medium.
MediumCollision homogeneousCollision(const Medium& m, float a, float b, Rng& rng) {
  const Rgb st = rgb(m.sigmaT()), ss = rgb(m.sigmaS);
  const int h = heroChannel(rng);
  const double d = double(b) - double(a);  // inf for an infinite medium
  const double u = std::min(rng.uniform(), 0.99999994f);
  const double x = st[h] > 0.0 ? -std::log1p(-u) / st[h] : kInf;  // double: sigma ~ 1e-45 stays finite
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

// Grid: delta tracking against the majorant, with the same one-sample MIS over the
// channels: the hero accepts a real collision with probability sigmaT_h(x) / majorant;
// f is the channels' contribution over the hero's path density, r each channel's path
// density over the hero's, and the weight f / mean(r) stays unbiased per channel.
MediumCollision gridCollision(const Medium& m, const Vec3& o, const Vec3& d, float a, float b, Rng& rng) {
  const DensityGrid& g = *m.density;
  const double mu = majorant(m);
  const float end = b;  // a flight without a collision reaches the segment's end, not the box's
  if (!(mu > 0.0) || !clipToBox(g, o, d, a, b)) return {false, end, Color(1.0f)};
  const Rgb st = rgb(m.sigmaT()), ss = rgb(m.sigmaS);
  const int h = heroChannel(rng);
  Rgb f{1.0, 1.0, 1.0}, r{1.0, 1.0, 1.0};
  double t = a;
  for (int step = 0; step < kMaxTrackingSteps; ++step) {
    t -= std::log1p(-double(std::min(rng.uniform(), 0.99999994f))) / mu;
    if (t >= b) {
      const double norm = mean(r);
      return {false, end, color({f[0] / norm, f[1] / norm, f[2] / norm})};
    }
    const double rho = g.at(o + float(t) * d);
    Rgb p;  // each channel's real-collision probability
    for (int c = 0; c < 3; ++c) p[c] = std::clamp(rho * st[c] / mu, 0.0, 1.0);
    if (rng.uniform() < p[h]) {
      // The real collision's event: f_c *= (rho sigmaS_c / majorant) / p_h and
      // r_k *= p_k / p_h; the p_h cancels in f / mean(r). r_h = 1, so the sum >= p_h.
      const double norm = (r[0] * p[0] + r[1] * p[1] + r[2] * p[2]) / 3.0;
      Rgb w;
      for (int c = 0; c < 3; ++c) w[c] = f[c] * rho * ss[c] / mu / norm;
      return {true, float(t), color(w)};
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
  }
  return {true, float(t), Color(0.0f)};  // opaque past the step limit: absorbed
}

// Grid: ratio tracking (Novák et al. 2014) with the same majorant; each channel's
// estimate is the product of its null fractions, 1 - sigmaT_c(x) / majorant.
Color gridTransmittance(const Medium& m, const Vec3& o, const Vec3& d, float a, float b, Rng& rng) {
  const DensityGrid& g = *m.density;
  const double mu = majorant(m);
  if (!(mu > 0.0) || !clipToBox(g, o, d, a, b)) return Color(1.0f);
  const Rgb st = rgb(m.sigmaT());
  Rgb tr{1.0, 1.0, 1.0};
  double t = a;
  for (int step = 0; step < kMaxTrackingSteps; ++step) {
    t -= std::log1p(-double(std::min(rng.uniform(), 0.99999994f))) / mu;
    if (t >= b) return color(tr);
    const double rho = g.at(o + float(t) * d);
    for (int c = 0; c < 3; ++c) tr[c] *= std::max(0.0, 1.0 - rho * st[c] / mu);
    const double tMax = std::max(tr[0], std::max(tr[1], tr[2]));
    if (!(tMax > 0.0)) return Color(0.0f);
    if (tMax < kRouletteBelow) {
      // Survive with probability tMax / kRouletteBelow: the survivors' estimate is
      // divided by it, so the mean is kept and thick media stop early.
      const double survive = tMax / kRouletteBelow;
      if (rng.uniform() >= survive) return Color(0.0f);
      for (double& c : tr) c /= survive;
    }
  }
  return Color(0.0f);
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
