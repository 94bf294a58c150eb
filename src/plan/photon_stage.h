// A render's photon maps as one value that several renders can share: emitted
// once (optionally recording smaller budgets as prefix cuts), then built into
// maps for the full budget or any recorded smaller one (penumbra sweep reuses
// them across k, depth, spp and the gate; runRender builds one and uses it).
#pragma once
#include "core/photon.h"
#include "core/scene.h"
#include "emit/emit.h"
#include "emit/emit_physical.h"
#include "gather/lookup_cache/lookup_cache.h"
#include "gather/photon_map.h"
#include "gather/volume_map.h"
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
  EmittedPhotons photons;  // every map's (the physical model emits the gate's shadow photons too)
  MapCounts budgets;       // what was emitted
  size_t numLights = 0;
  double seconds = 0.0;
  std::vector<std::string> notes;
};

// Which maps to emit and build: the render plan's photon passes (plan/render_plan.h).
struct PhotonNeeds {
  PerMap<bool> maps;
  // Per light, the share of photons of use to each map (the plan's splitByReach);
  // empty: budgets split by power. A function of the scene, so equal for every view.
  PerMap<std::vector<float>> reach;
  bool any() const {
    for (bool m : maps.values) if (m) return true;
    return false;
  }
  PhotonNeeds& operator|=(const PhotonNeeds& o) {
    for (MapKind k : kAllMaps) {
      maps[k] = maps[k] || o.maps[k];
      if (reach[k].empty()) reach[k] = o.reach[k];
    }
    return *this;
  }
};
PhotonNeeds photonNeeds(const RenderPlan& plan);

// What makes two renders' photon stages equal: the geometry, every setting that
// changes which photons are emitted (plan/reuse_key.h), the budgets and the maps read.
struct PhotonStageKey {
  std::string geometry, photons;
  MapCounts budgets;
  PerMap<bool> maps;
  bool operator==(const PhotonStageKey& o) const {
    return geometry == o.geometry && photons == o.photons && budgets == o.budgets && maps == o.maps;
  }
};

// The photons the plan's passes emit per map (0 for a pass that is off).
MapCounts planBudgets(const RenderPlan& plan);

// Emits `budgets` of the maps in `needs` for progressive pass `pass`, recording
// `smaller` budgets. `progress` (if any) expects the photons asked for and counts
// each batch traced.
Emission emitPhotonsFor(const Scene& scene, const TraceScene& tracer, const PhotonNeeds& needs,
                        const MapCounts& budgets, uint32_t pass, const std::vector<uint64_t>& smaller = {},
                        ProgressCounter* progress = nullptr);

// Built photon maps and what they cost.
struct PhotonStage {
  MapSlots<PhotonMapFor> maps;
  float classicScale = 1.0f;
  MapCounts budgets;
  MapCounts emitted;
  double emitSeconds = 0.0, buildSeconds = 0.0;
  bool fromPrefix = false;  // cut out of a larger emission
  std::vector<std::string> notes;
  // Precomputed lookups built from these maps (camera-independent), and the
  // parameters they were built with: a later frame with equal ones reuses them.
  // `lookup` holds the light map's estimate (and the gate's verdicts, where they share
  // cells); `gateLookup` the gate's verdicts where they want finer cells than it.
  LookupCache lookup, gateLookup;
  std::optional<LookupCacheParams> lookupKey, gateLookupKey;
  double lookupSeconds = 0.0;  // what building the lookups took
  size_t bytes() const {
    size_t n = lookup.memoryBytes() + gateLookup.memoryBytes();
    maps.forEach([&n](MapKind, const auto& map) { n += map.memoryBytes(); });
    return n;
  }
};

// Maps for `budgets` out of `emission`: the full budgets (then the photons are
// moved out when `consume`, else copied) or a recorded smaller one. Returns false,
// leaving `stage` untouched, when some map's budget is neither.
// `progress` (if any) expects 2 units per photon and counts them (MapBuildOptions).
bool buildStage(Emission& emission, const MapCounts& budgets, bool consume, PhotonStage& stage,
                ProgressCounter* progress = nullptr);

}  // namespace penumbra
