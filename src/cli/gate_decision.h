// Whether the shadow gate pays for itself in one render (photons.gate: auto): a
// cost model over the frame's shading points, light samples and shadow photons.
#pragma once
#include "core/scene.h"
#include <string>

namespace penumbra {

struct GateDecision {
  bool gate = false;
  double savedMs = 0.0;  // estimated shadow-ray time the gate would avoid (one core)
  double costMs = 0.0;   // estimated photon pass + lookup time it would add (one core)
  std::string reason;    // one line for the summary and --stats
};

// Per-operation costs measured on this project's machine (docs/PERFORMANCE.md:
// bench_lookup, bench_photons). Constants, not timings taken at render time, so
// the decision and therefore the image are the same on every run.
struct GateCosts {
  double shadowRayNs = 50.0;     // rtcOccluded1 to a light, bench_lookup
  double avoidable = 0.85;       // share of shadow tests a gate decides (soft_shadows: 85%)
  double lookupNs = 80.0;        // one precomputed query per shading point, all lights
  double exactVoteNs = 3000.0;   // one k-nearest vote per light per shading point
  double shadowPhotonNs = 520.0; // emit + build + cache, per emitted shadow photon
};

GateDecision decideGate(const Scene& scene, const GateCosts& costs = {});

}  // namespace penumbra
