// The lookup cost model: every shading point's exact gate votes and gathers, against
// one cache query per point plus the exact answers of the cells the queries fill.
#include "plan/lookup_decision.h"
#include "plan/cost_model.h"
#include "plan/resource_estimate.h"
#include "plan/transport_model.h"
#include <algorithm>
#include <fmt/format.h>

namespace penumbra {

namespace {

// Precomputed lookups blur the estimate to the cell size; they are chosen only where
// they cut the lookup time at least by this factor.
constexpr double kRequiredSaving = 2.0;

}  // namespace

LookupDecision decideLookup(const Scene& scene, int gatedLights, const IndirectLookup& gather, double gatherPhotons,
                            int cameraPasses) {
  using namespace cost;
  LookupDecision d;
  const PhotonSettings& ps = scene.photons;
  // Camera hits bound the shading points from below (progressive passes repeat them).
  const double points = double(scene.camera.width) * scene.camera.height * scene.camera.spp * cameraPasses;
  const int gatherK = gather.k;
  const double nsPerNeighbour = gatherNsPerNeighbour(gather.nsPerNeighbour, mapBytes(gather.map, gatherPhotons));
  const double perPointNs = gatedLights * kExactVoteNs + (gatherPhotons > 0.0 ? gatherK * nsPerNeighbour : 0.0);
  // A cell per k photons' neighbourhood, twice over for the surfaces' two sides (the
  // resource estimate's cache size), each answered once exactly.
  const int k = std::max(1, gatherPhotons > 0.0 ? gatherK : ps.kShadow);
  const double photons = gatherPhotons > 0.0 ? gatherPhotons : double(ps.shadowPhotons);
  const double cells = std::min(points, 2.0 * photons / k);
  d.exactMs = points * perPointNs * 1e-6;
  d.precomputedMs = (points * kLookupNs + cells * perPointNs) * 1e-6;
  d.precomputed = d.exactMs > kRequiredSaving * d.precomputedMs;
  d.reason = fmt::format("auto: {}: exact gathers ~{:.0f} ms against ~{:.0f} ms of cache queries and cells",
                         d.precomputed ? "precomputed" : "exact", d.exactMs, d.precomputedMs);
  return d;
}

}  // namespace penumbra
