// The global map's gather where no light arrives directly (an umbra, or a face turned
// from every light): narrower than elsewhere, since there its bias is all the error.
#pragma once
#include "gather/radiance_estimate.h"
#include <algorithm>
#include <cmath>

namespace penumbra {

// A kernel estimate's smoothing bias grows as r^2 (as k, at a given density) and lifts
// the dark floor of a contact shadow, and a k-nearest radius is widest where photons are
// sparse, as they are there. Where direct light dominates that bias is a small share of
// the pixel; where no light arrives directly the global estimate is the whole pixel.
// There a k-nearest gather takes this share of the photons: a third of the radius, an
// eighth of the bias, sqrt(8) times the noise of a dark pixel, which the passes average.
// A fixed radius (photons.radius) is the user's and stays.
constexpr double kUmbraGatherShare = 0.125;

inline PhotonGather umbraGather(const PhotonGather& g) {
  PhotonGather u = g;
  if (g.k > kMinPassK) u.k = std::max(kMinPassK, static_cast<int>(std::lround(g.k * kUmbraGatherShare)));
  return u;
}

}  // namespace penumbra
