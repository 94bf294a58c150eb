// Closed forms for a homogeneous medium along a ray: Beer–Lambert transmittance,
// free-flight distances, and equiangular distances towards a point (Kulla & Fajardo 2012).
#pragma once
#include "core/math.h"
#include <algorithm>
#include <cmath>

namespace penumbra {

// exp(-sigma d) for one channel, in double: 1 where sigma is 0 (even over an infinite
// distance, where sigma d would be NaN), 0 where sigma d overflows; never NaN.
inline double opticalExp(double sigma, double d) {
  if (!(sigma > 0.0) || !(d > 0.0)) return 1.0;
  return std::exp(-sigma * d);
}

// exp(-sigmaT d) per channel; 0 where sigmaT is infinite, 1 over no distance.
inline Color transmittance(const Color& sigmaT, float d) {
  return Color(float(opticalExp(sigmaT.r, d)), float(opticalExp(sigmaT.g, d)), float(opticalExp(sigmaT.b, d)));
}

// The free-flight distance -ln(1 - u) / s for s > 0, in double (an s near the
// smallest float keeps a finite distance); u below 1 so the log stays finite.
inline double freeFlightDistance(double s, float u) { return -std::log1p(-double(std::min(u, 0.99999994f))) / s; }

// A free-flight distance drawn with density s exp(-s t); may exceed the segment.
// s = 0 never collides: infinity (not 0 / 0 at u = 0).
inline float sampleFreeFlight(float s, float u) {
  if (!(s > 0.0f)) return kInf;
  return float(freeFlightDistance(double(s), u));
}

// A distance along a ray and its density per unit length.
struct DistanceSample {
  float t = 0.0f;
  float pdf = 0.0f;  // 0: no sample (an empty segment)
};
using EquiangularSample = DistanceSample;

// A free flight truncated to [0, d]: density s exp(-s t) / (1 - exp(-s d)), so every
// sample lands in the segment (distance sampling for single scattering). Uniform for
// s = 0; a plain free flight for d = inf; no sample for an empty or s = 0 infinite one.
inline double truncatedFreeFlightPdf(float s, float d, float t) {
  if (!(t >= 0.0f && t <= d)) return 0.0;
  if (!(s > 0.0f)) return std::isfinite(d) && d > 0.0f ? 1.0 / d : 0.0;
  const double mass = std::isfinite(d) ? -std::expm1(-double(s) * d) : 1.0;  // 1 - e^{-sd}, no cancellation
  return mass > 0.0 ? double(s) * std::exp(-double(s) * t) / mass : 0.0;
}
inline DistanceSample sampleTruncatedFreeFlight(float s, float d, float u) {
  if (!(d > 0.0f) || (!(s > 0.0f) && !std::isfinite(d))) return {0.0f, 0.0f};
  float t;
  if (!(s > 0.0f)) {
    t = u * d;
  } else {
    const double mass = std::isfinite(d) ? -std::expm1(-double(s) * d) : 1.0;
    t = float(-std::log1p(-double(std::min(u, 0.99999994f)) * mass) / double(s));
  }
  t = std::clamp(t, 0.0f, d);
  return {t, float(truncatedFreeFlightPdf(s, d, t))};
}

// Distances in [a, b] along a ray (origin o, unit dir d) with density proportional to
// 1 / |x(t) - p|^2: uniform in the angle subtended at p. In double: b = inf puts thetaB
// at pi/2, whose float rounding would flip the tangent's sign.
struct EquiangularFrame {
  double delta = 0.0;  // the ray parameter closest to p
  double dist = 0.0;   // p's distance from the ray's line (floored: p on the line)
  double thetaA = 0.0, thetaB = 0.0;
  EquiangularFrame(const Vec3& o, const Vec3& d, const Vec3& p, float a, float b) {
    const glm::dvec3 op = glm::dvec3(p) - glm::dvec3(o), dd(d);
    delta = glm::dot(op, dd);
    dist = std::max(glm::length(op - delta * dd), 1e-7);
    thetaA = std::atan2(double(a) - delta, dist);
    thetaB = std::atan2(double(b) - delta, dist);
  }
  double pdf(double t) const { return dist / ((thetaB - thetaA) * (dist * dist + (t - delta) * (t - delta))); }
  // A distance in [a, b] (the frame's own) drawn uniformly in angle; no sample when the
  // segment subtends no angle.
  EquiangularSample sample(float u, float a, float b) const {
    if (!(thetaB > thetaA)) return {a, 0.0f};
    const double theta = thetaA + double(u) * (thetaB - thetaA);
    const float t = std::clamp(float(delta + dist * std::tan(theta)), a, b);
    return {t, float(pdf(t))};
  }
};
// The density sampleEquiangular draws t with (0 outside [a, b]): for MIS against
// distance sampling, which evaluates it at its own t.
inline float equiangularPdfAt(const Vec3& o, const Vec3& d, const Vec3& p, float a, float b, float t) {
  if (!(t >= a && t <= b)) return 0.0f;
  const EquiangularFrame f(o, d, p, a, b);
  return f.thetaB > f.thetaA ? float(f.pdf(t)) : 0.0f;
}
inline EquiangularSample sampleEquiangular(const Vec3& o, const Vec3& d, const Vec3& p, float a, float b, float u) {
  return EquiangularFrame(o, d, p, a, b).sample(u, a, b);
}

// Veach's power heuristic (beta = 2) for a sample of the strategy with density pdfThis
// against one with pdfOther (each times its sample count). As a ratio: no overflow of
// the squares for pdfs near 1e30, and 0 (not NaN) where neither can sample.
inline float powerHeuristicWeight(float pdfThis, float pdfOther) {
  if (!(pdfThis > 0.0f)) return 0.0f;
  if (!(pdfOther > 0.0f)) return 1.0f;
  if (std::isinf(pdfThis)) return std::isinf(pdfOther) ? 0.5f : 1.0f;
  const double r = double(pdfOther) / double(pdfThis);
  return float(1.0 / (1.0 + r * r));
}

}  // namespace penumbra
