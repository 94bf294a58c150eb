// Where each light's photons can be of use to a map: a short pilot emission that
// measures, per light, the fraction of photons whose first hit can start a stored path.
// The photon budgets are split by power times this fraction (issue: budgets go where they matter).
#pragma once
#include "core/scene.h"
#include "geometry/trace_scene.h"
#include <cstdint>
#include <vector>

namespace penumbra {

// What a map's photons must first hit for the map to store anything of them. (The
// classic estimator has no rule: it averages photon colours, so it keeps the power split.)
enum class ReachRule : uint8_t {
  Bouncing,    // density estimator: stored from the second hit on, so p_r or p_t > 0
  Scattering,  // physical global map: stored after a bounce, so a BSDF that returns power
  Specular,    // physical caustic map: stored after a specular bounce (delta lobe)
};

// Pilot photons per light. A light none of whose pilots reaches gets no photons;
// by the rule of three the share of its photons that could have been stored is then
// below 3 / kReachPilots with 95% confidence, so the flux dropped is at most that
// share of the light's emitted power (of the map's flux it can be more, when that
// light is the map's only source).
constexpr uint32_t kReachPilots = 1024;

// Per light, the fraction of `pilots` photons (their own random stream, seeded by the
// scene's seed and the light's index) whose first hit satisfies `rule`. Lights that
// emit no photons get 0. Identical for any thread count.
std::vector<float> measureReach(const Scene& scene, const TraceScene& tracer, ReachRule rule,
                                uint32_t pilots = kReachPilots);

// The physical global map stores from a photon's second hit on: the share of
// `pilots` photons per emitting light (a stream of their own) whose first hit
// scatters and whose bounce, sampled from that surface's BSDF, lands on a surface.
// 0 means no global photon can be stored (a lone convex model under a sky: every
// bounce leaves), up to the rule of three as for the reach.
float measureRebound(const Scene& scene, const TraceScene& tracer, uint32_t pilots = kReachPilots);

// Whether a first hit on `material` satisfies `rule`.
bool reaches(const Scene& scene, int material, ReachRule rule);

// `weights` times `reach` (empty reach: unchanged), for the budget split.
std::vector<double> reachWeighted(std::vector<double> weights, const std::vector<float>& reach);

}  // namespace penumbra
