// A render's photon maps as one value that several renders can share: emitted
// once (optionally recording smaller budgets as prefix cuts), then built into
// maps for the full budget or any recorded smaller one (penumbra sweep reuses
// them across k, depth, spp and the gate; runRender builds one and uses it).
#pragma once
#include "core/photon.h"
#include "core/scene.h"
#include "emit/emit.h"
#include "emit/emit_physical.h"
#include "gather/lookup_cache.h"
#include "gather/photon_map.h"
#include "geometry/trace_scene.h"
#include "plan/render_plan.h"
#include "plan/reuse_key.h"
#include "trace/render.h"
#include <algorithm>
#include <optional>
#include <string>
#include <vector>

namespace penumbra {


// One emission (pass 0 of the physical model, or the classic pass) with the raw
// photons of every map the view reads, and the prefix cuts asked for.
struct Emission {
  bool physical = false;
  PhotonMaps classic;          // classic maps; the physical model's gate photons (shadow)
  ClassicCuts classicCuts;
  PhysicalPhotons photons;     // physical caustic and global photons
  MapBudgets budgets;       // what was emitted
  size_t numLights = 0;
  double seconds = 0.0;
  std::vector<std::string> notes;
};

// Which maps to emit and build: the render plan's photon passes (plan/render_plan.h).
struct PhotonNeeds {
  bool shadow = false, indirect = false, global = false, caustic = false;
  // Per light, the share of photons of use to each map (the plan's splitByReach);
  // empty: budgets split by power. A function of the scene, so equal for every view.
  std::vector<float> indirectReach, globalReach, causticReach;
  bool any() const { return shadow || indirect || global || caustic; }
  PhotonNeeds& operator|=(const PhotonNeeds& o) {
    shadow |= o.shadow; indirect |= o.indirect; global |= o.global; caustic |= o.caustic;
    if (indirectReach.empty()) indirectReach = o.indirectReach;
    if (globalReach.empty()) globalReach = o.globalReach;
    if (causticReach.empty()) causticReach = o.causticReach;
    return *this;
  }
};
PhotonNeeds photonNeeds(const RenderPlan& plan);

// What makes two renders' photon stages equal: the geometry, every setting that
// changes which photons are emitted (plan/reuse_key.h), the budgets and the maps read.
struct PhotonStageKey {
  std::string geometry, photons;
  MapBudgets budgets;
  bool shadow = false, indirect = false, global = false, caustic = false;
  bool operator==(const PhotonStageKey& o) const {
    return geometry == o.geometry && photons == o.photons && budgets == o.budgets && shadow == o.shadow &&
           indirect == o.indirect && global == o.global && caustic == o.caustic;
  }
};

// The photons the plan's passes emit per map (0 for a pass that is off).
MapBudgets planBudgets(const RenderPlan& plan);

// Emits `budgets` of the maps in `needs` for progressive pass `pass`, recording
// `smaller` budgets. `progress` (if any) expects the photons asked for and counts
// each batch traced.
Emission emitPhotonsFor(const Scene& scene, const TraceScene& tracer, const PhotonNeeds& needs,
                        const MapBudgets& budgets, uint32_t pass, const std::vector<uint64_t>& smaller = {},
                        ProgressCounter* progress = nullptr);

// Built photon maps and what they cost.
struct PhotonStage {
  ShadowPhotonMap shadow;
  IndirectPhotonMap indirect, caustic, global;
  float classicScale = 1.0f;
  MapBudgets budgets;
  uint64_t emittedShadow = 0, emittedIndirect = 0, emittedCaustic = 0, emittedGlobal = 0;
  double emitSeconds = 0.0, buildSeconds = 0.0;
  bool fromPrefix = false;  // cut out of a larger emission
  std::vector<std::string> notes;
  // Precomputed lookups built from these maps (camera-independent), and the
  // parameters they were built with: a later frame with equal ones reuses them.
  LookupCache lookup;
  std::optional<LookupCacheParams> lookupKey;
  double lookupSeconds = 0.0;  // what building `lookup` took
  size_t bytes() const {
    return shadow.memoryBytes() + indirect.memoryBytes() + caustic.memoryBytes() + global.memoryBytes() +
           lookup.memoryBytes();
  }
};

// Maps for `budgets` out of `emission`: the full budgets (then the photons are
// moved out when `consume`, else copied) or a recorded smaller one. Returns false,
// leaving `stage` untouched, when some map's budget is neither.
// `progress` (if any) expects 2 units per photon and counts them (MapBuildOptions).
bool buildStage(Emission& emission, const MapBudgets& budgets, bool consume, PhotonStage& stage,
                ProgressCounter* progress = nullptr);

}  // namespace penumbra
