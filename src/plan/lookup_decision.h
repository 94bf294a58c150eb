// Whether precomputed lookups pay in one render (photons.lookup: auto): exact gathers
// at every shading point against one query each plus the cells that answer them.
#pragma once
#include "core/scene.h"
#include <string>

namespace penumbra {

struct LookupDecision {
  bool precomputed = false;
  double exactMs = 0.0;        // estimated exact votes and gathers (one core)
  double precomputedMs = 0.0;  // estimated queries plus the cells they read (one core)
  std::string reason;          // one line for the plan and --stats
};

// `gatedLights` lights the gate answers (0: gate off); `gatherK` the neighbours of
// the model's per-cell estimate and `gatherPhotons` the photons its map stores per
// pass (0: no such map); `cameraPasses` the times camera hits repeat (the model's
// progressive passes); `nsPerNeighbour` the model's exact gather per neighbour from a
// cached map (IndirectLookup). Costs are plan/cost_model.h's.
LookupDecision decideLookup(const Scene& scene, int gatedLights, int gatherK, double gatherPhotons, int cameraPasses,
                            double nsPerNeighbour);

}  // namespace penumbra
