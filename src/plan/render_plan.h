// The render plan: before any work, what a render of this scene, view and settings
// runs, each pass with its budget and the reason, as plain data. The stages read
// its decisions beside the settings; `penumbra plan` prints it; --stats holds it.
#pragma once
#include "core/map_kind.h"
#include "core/scene.h"
#include "geometry/trace_scene.h"
#include "trace/render.h"
#include "trace/shading.h"
#include <array>
#include <cstdint>
#include <string>
#include <vector>

namespace penumbra {

enum class Pass : uint8_t {
  Gate,             // shadow photons, their map, and the verdicts that replace shadow rays
  IndirectPhotons,  // classic indirect map
  GlobalPhotons,    // physical global map
  CausticPhotons,   // physical caustic map
  VolumePhotons,    // physical volume map: photons scattered in media (scenes with a medium)
  ShadowRays,
  Reflection,       // mirror and glass-reflected recursion
  Refraction,       // glass-transmitted recursion
  Textures,
  LightSamples,     // stratified samples per area light
  Packets,          // camera and primary shadow rays as Embree packets
  Precompute,       // photons.lookup = precomputed: per-cell verdicts and estimates
  Count
};
constexpr size_t kPassCount = static_cast<size_t>(Pass::Count);

// The pass that emits and builds a map (the gate's is the shadow map).
constexpr Pass photonPass(MapKind k) {
  constexpr Pass kPasses[kMapKinds] = {Pass::Gate, Pass::IndirectPhotons, Pass::GlobalPhotons, Pass::CausticPhotons,
                                        Pass::VolumePhotons};
  return kPasses[static_cast<size_t>(k)];
}

// "gate", "indirect-photons", ...: the names --enable / --disable take.
const char* passName(Pass pass);
// Throws InputError naming the known passes.
Pass parsePass(const std::string& name);

struct PassDecision {
  bool on = false;
  std::string reason;               // why, e.g. "off (no transparent material)"
  uint64_t budget = 0;              // photons (photon passes), samples (light samples)
  std::vector<uint64_t> perLight;   // photon passes: the budget's split over lights
  std::vector<float> reach;         // photon passes: per light, the share of photons of use (splitByReach)
  bool overridden = false;          // set by --enable / --disable
  bool changesImage = false;        // ... and the override can change the image
};

class TransportModel;

struct RenderPlan {
  std::array<PassDecision, kPassCount> passes;
  Aov aov = Aov::Beauty;
  const TransportModel* model = nullptr;  // the scene's transport model (transportOf)
  PassDecision& operator[](Pass p) { return passes[static_cast<size_t>(p)]; }
  const PassDecision& operator[](Pass p) const { return passes[static_cast<size_t>(p)]; }
};

struct PlanOverrides {
  std::vector<Pass> enable, disable;
};

// Decides every pass from the scene (photons.gate = auto already resolved or not:
// the plan resolves it), the view and the overrides.
RenderPlan makePlan(const Scene& scene, Aov aov, const PlanOverrides& overrides = {});

// The plan's decisions the tracer reads (gate, shadows, recursion, light samples,
// packets), beside `scene`'s settings, which stay as the user gave them. The photon
// budgets are planBudgets (plan/photon_stage.h); textures the session's.
FrameChoices choicesOf(const RenderPlan& plan, const Scene& scene);
// photons.lookup = precomputed, unless the plan found nothing to precompute.
inline bool precomputedLookups(const RenderPlan& plan) { return plan[Pass::Precompute].on; }

// Once the BVH exists, before any photon: the indirect, global and caustic passes'
// budgets split over the lights by power times the share of each light's photons
// whose first hit can lead to a store (a pilot of emit/light_reach.h's kReachPilots
// photons per light); a light that reaches nothing gets none, a pass whose lights
// all reach nothing goes off; the reason says which. Overridden passes keep the
// power split (forced on means everything).
void splitByReach(RenderPlan& plan, const Scene& scene, const TraceScene& tracer);

// One line per pass: "refraction      off  (no transparent material)".
std::string planText(const RenderPlan& plan);
// The plan as a JSON object (for --stats): {"gate": {"on": false, "reason": ...}, ...}.
std::string planJson(const RenderPlan& plan);

}  // namespace penumbra
