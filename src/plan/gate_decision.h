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
  bool stratified = false;  // on, with cells that vote per stratum of an area light
  std::string reason;    // one line for the summary and --stats
};

// The shadow-ray, lookup and shadow-photon costs of plan/cost_model.h. Lookups that
// are not exact count as precomputed: lookup auto precomputes wherever votes dominate.
GateDecision decideGate(const Scene& scene);

// The share of a gated light's shadow tests the gate answers without a ray:
// higher for an area light whose strata precomputed cells vote on one by one.
double avoidableShare(const Light& light, bool precomputed);

// Lights whose shadow tests the gate can answer: lit ones that emit shadow photons
// (not directional, not the environment).
int gatedLightCount(const Scene& scene);

}  // namespace penumbra
