// A pilot emission: a few thousand photons through the real emitters, to measure
// how many records each emitted photon leaves behind in this scene.
#pragma once
#include "plan/resource_estimate.h"
#include "geometry/trace_scene.h"

namespace penumbra {

// Photons per map the pilot emits at most (each light gets its share).
constexpr uint64_t kPilotPhotons = 4096;

// Measured stores per emitted photon for the maps in `plan`, with a safety margin
// for the pilot's sampling error, never above `bound` (the analytic rates).
StoreRates measureStoreRates(const Scene& scene, const TraceScene& tracer, const PhotonPlan& plan,
                             const StoreRates& bound);

}  // namespace penumbra
