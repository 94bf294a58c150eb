// Indirect-light estimators over gathered photons: the cone-weighted `classic`
// average (the student report's) and Jensen's cone-filtered irradiance `density`.
#pragma once
#include "core/math.h"
#include "core/photon.h"
#include "gather/kd_tree.h"
#include <cstddef>

namespace penumbra {

// A photon contributes to the indirect estimate only if its normal . n exceeds this:
// photons on the back of a thin wall (opposite normal) or around a sharp corner
// (perpendicular normal) describe other surfaces.
constexpr float kIndirectMinNormalCos = 0.5f;

struct IndirectEstimate {
  Color value{0.0f};
  int found = 0;      // photons that passed the normal filter
  float dMax = 0.0f;  // distance to the farthest of them
};

// Both take the count nearest photons listed in scratch (indices/dist2; any order
// gives the same value up to float rounding, so callers pass a canonical one) and
// compact the ones passing the normal filter to the front of scratch.
// Weight w_i = 1 - d_i / d_max; all-coincident photons (d_max = 0) get w = 1.
//   classic: sum(w_i * power_i) / found                 (0 if nothing passed)
//   density: sum(w_i * power_i) / ((1 - 2/3) * pi * d_max^2)   (0 if d_max = 0)
// The density form's 1/3 is the cone filter's normalisation (Jensen, k = 1): for
// photons uniform in the disc, E[w] = 1/3, which makes it an unbiased irradiance
// estimate on uniformly lit surfaces.
IndirectEstimate classicEstimate(const IndirectPhoton* photons, GatherScratch& scratch,
                                 size_t count, const Vec3& n,
                                 float minNormalCos = kIndirectMinNormalCos);
IndirectEstimate densityEstimate(const IndirectPhoton* photons, GatherScratch& scratch,
                                 size_t count, const Vec3& n,
                                 float minNormalCos = kIndirectMinNormalCos);

}  // namespace penumbra
