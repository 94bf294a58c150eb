// The physical model's photon density estimate: reflected radiance from the
// photons around a point, weighted by the BSDF and Silverman's (Epanechnikov) kernel.
#pragma once
#include "core/bsdf.h"
#include "gather/photon_map.h"
#include <cstdint>

namespace penumbra {

struct RadianceEstimate {
  Color value{0.0f};
  int found = 0;        // photons that passed the normal filter
  float radius = 0.0f;  // the kernel's radius
  // When the gather asks (PhotonGather::probeSmoothing): the estimate's smoothing bias,
  // 2 (L_r - L_{r/sqrt2}) from the same photons (see photonRadiance); else 0.
  Color smoothing{0.0f};
};

// Which photons an estimate reads: the k nearest closer than maxRadius (0: at any
// distance), the kernel's radius r the k-th one's distance, or maxRadius when fewer
// than k lie inside it; with k = 0, every photon closer than maxRadius (r = maxRadius).
struct PhotonGather {
  int k = 0;
  float maxRadius = 0.0f;
  bool probeSmoothing = false;  // also estimate the smoothing bias (RadianceEstimate::smoothing)
};

// L(x, wo) = sum_i K(d_i) f(wo, wi_i) Phi_i with K(d) = 2 / (pi r^2) (1 - d^2 / r^2),
// over the photons whose stored normal agrees with frame.ng (cos > 0.5). The kernel
// integrates to 1 over the disc, so a uniformly lit plane gets exactly f Phi / area
// in expectation (k nearest: the k-th photon weighs 0, so the other k - 1 over the
// disc's area, as the unbiased estimate of a Poisson density). Where the disc reaches
// past the surface's edge (photons of a neighbouring surface at an angle to it mark
// the edge: surface_share.h), only photons on the query's side count, over the
// kernel's mass on that side; the density-estimation bias left is that of a curved
// density (-> 0 with r), and a caustic is blurred over about r.
// That bias grows as r^2 (the kernel's second moment times the density's curvature),
// and the same estimate over the inner disc of radius r/sqrt2 has half of it and the
// same expected value on a uniform density (each disc's photons are uniform in it),
// so 2 (L_r - L_{r/sqrt2}) estimates the bias of L_r, its noise left to the caller.
RadianceEstimate photonRadiance(const IndirectPhotonMap& map, const Bsdf& bsdf, const BsdfFrame& frame,
                                const Vec3& p, const Vec3& wo, const PhotonGather& gather,
                                GatherScratch& scratch);

// The median distance to the k-th nearest photon, measured at up to 256 photons
// spread evenly through the map's storage order: the lookup cache's cell scale and
// the typical radius --stats reports. Deterministic; 0 for an empty map.
float typicalKnnRadius(const IndirectPhotonMap& map, int k, GatherScratch& scratch);

// Progressive passes (Knaus & Zwicker 2011): pass i's (0-based) squared gather radius
// as a share of the first pass's, prod_{j=1..i} (j + alpha) / (j + 1), which falls as
// i^(alpha - 1) / Gamma(1 + alpha). alpha = 1 keeps it 1.
double passRadiusShare(uint32_t pass, float alpha);

// The photons a k-nearest gather takes in pass i: k x passRadiusShare, rounded, at
// least kMinPassK. At a given photon density the k-th neighbour's squared distance is
// proportional to k, so every point's radius shrinks by the schedule above from its
// own first-pass radius: narrow in a dense caustic, wide where photons are sparse.
constexpr int kMinPassK = 2;  // the k-th photon weighs 0: one more than it must count
int passK(int k, uint32_t pass, float alpha);

}  // namespace penumbra
