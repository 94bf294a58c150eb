// The physical model's photon density estimate: reflected radiance from the
// photons around a point, weighted by the BSDF and Silverman's (Epanechnikov) kernel.
#pragma once
#include "core/bsdf.h"
#include "gather/photon_map.h"

namespace penumbra {

struct RadianceEstimate {
  Color value{0.0f};
  int found = 0;        // photons that passed the normal filter
  float radius = 0.0f;  // the kernel's radius
};

// L(x, wo) = sum_i K(d_i) f(wo, wi_i) Phi_i with K(d) = 2 / (pi r^2) (1 - d^2 / r^2),
// over the photons whose stored normal agrees with frame.ng (cos > 0.5). With
// radius > 0 every photon closer than radius counts (progressive passes); with
// radius == 0 the k nearest do and r is the k-th one's distance. The kernel
// integrates to 1 over the disc, so a uniformly lit plane gets exactly f Phi / area
// in expectation; near edges and corners the estimate is biased low by the part of
// the disc that holds no surface (the usual density-estimation bias, -> 0 with r).
RadianceEstimate photonRadiance(const IndirectPhotonMap& map, const Bsdf& bsdf,
                                const BsdfFrame& frame, const Vec3& p, const Vec3& wo, int k,
                                float radius, GatherScratch& scratch);

// The median distance to the k-th nearest photon, measured at up to 256 photons
// spread evenly through the map's storage order: the first progressive pass's
// radius when none is given. Deterministic; 0 for an empty map.
float typicalKnnRadius(const IndirectPhotonMap& map, int k, GatherScratch& scratch);

}  // namespace penumbra
