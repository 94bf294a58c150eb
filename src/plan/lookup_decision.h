// Whether precomputed lookups pay in one render (photons.lookup: auto): exact gathers
// at every shading point against one query each plus the cells that answer them.
#pragma once
#include "core/scene.h"
#include <string>

namespace penumbra {

struct IndirectLookup;

struct LookupDecision {
  bool precomputed = false;
  double exactMs = 0.0;        // estimated exact votes and gathers (one core)
  double precomputedMs = 0.0;  // estimated queries plus the cells they read (one core)
  std::string reason;          // one line for the plan and --stats
};

// `gatedLights` lights the gate answers (0: gate off); `gather` the model's per-cell
// estimate (its map, neighbours and exact price per neighbour) and `gatherPhotons` the
// photons its map stores per pass (0: no such map); `cameraPasses` the times camera
// hits repeat (the model's progressive passes). Costs are plan/cost_model.h's.
LookupDecision decideLookup(const Scene& scene, int gatedLights, const IndirectLookup& gather, double gatherPhotons,
                            int cameraPasses);

}  // namespace penumbra
