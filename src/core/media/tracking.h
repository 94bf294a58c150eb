// Travel through one medium along a ray: transmittance and collision sampling, in
// closed form for a homogeneous medium and by tracking against the majorant in a grid
// (delta tracking for collisions, ratio tracking for transmittance; Novák et al. 2018).
#pragma once
#include "core/media/medium.h"
#include "core/rng.h"

namespace penumbra {

// Transmittance over [a, b] of the ray o + t d (d unit): exp(-integral sigmaT) per
// channel. Exact for a homogeneous medium (no draws); an unbiased ratio-tracking
// estimate in a grid (draws from rng).
Color mediumTransmittance(const Medium& m, const Vec3& o, const Vec3& d, float a, float b, Rng& rng);

// One free flight from a towards b: a real collision at t < b, or none (t = b, which
// may be inf). `weight` multiplies the path's throughput so that every estimate stays
// unbiased for RGB coefficients: on a collision it is sigmaS(x) T(a, t) / pdf(t) (the
// scattering albedo is in it: a path that continues scatters there); without one it
// is T(a, b) / P(no collision). The distance follows one channel's sigmaT chosen
// uniformly and the weight is the balance heuristic over the three channels, so each
// channel's weight is at most 3 x its albedo; a grey medium gives exactly the albedo
// and 1. A weight of 0 ends the path (a grid too thick to track: see tracking.cpp).
struct MediumCollision {
  bool collided = false;
  float t = 0.0f;
  Color weight{1.0f};
};
MediumCollision sampleCollision(const Medium& m, const Vec3& o, const Vec3& d, float a, float b, Rng& rng);

// The majorant tracking steps against: the largest channel of sigmaT times the grid's
// largest density (homogeneous: the largest channel). A grid segment of length L costs
// about majorant x L density lookups, for the cost model and the counters.
float mediumMajorant(const Medium& m);

// sigmaS, sigmaT and the emission source (sigmaA x Le) at a point: the medium's
// coefficients times its density there.
Color sigmaSAt(const Medium& m, const Vec3& p);
Color sigmaTAt(const Medium& m, const Vec3& p);
Color emissionAt(const Medium& m, const Vec3& p);

}  // namespace penumbra
