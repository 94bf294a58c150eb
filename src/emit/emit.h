// The photon pass: point lights shoot shadow photons (kept along their whole
// line) and indirect photons (bounced by Russian roulette) through the tracer's
// Embree scene, in fixed-size batches scheduled by oneTBB.
#pragma once
#include "core/light_sample.h"
#include "core/photon.h"
#include "core/photon_batches.h"
#include "core/progress.h"
#include "core/scene.h"
#include "emit/photon_prefix.h"
#include "geometry/trace_scene.h"
#include "core/map_kind.h"
#include <algorithm>
#include <optional>

namespace penumbra {

struct EmitOptions {
  MapCounts budgets;  // photons to emit per map: the render plan's (plan/photon_stage.h: planBudgets)
  uint32_t batchSize = 4096;  // photons per task; each batch owns one random stream
  int maxHitsPerLine = 64;    // shadow photons kept per line at most
  // The maps to emit (false: nobody reads it, e.g. the gate's shadow photons under
  // --aov indirect); each emitter skips the maps of the other model.
  PerMap<bool> maps{{true, true, true, true, true}};
  // Smaller budgets to record inside this emission (emit/photon_prefix.h), for every
  // map emitted: a budget below a map's own is cut out of it afterwards.
  std::vector<uint64_t> prefixBudgets;
  // Per light, the fraction of its photons that reach where each map stores
  // (emit/light_reach.h; the render plan measures it): budgets are split by power
  // times this. Empty: by power alone. The gate's shadow photons keep the power split.
  PerMap<std::vector<float>> reach;
  // Each finished batch adds its photon count (one atomic add per batch); null: none.
  ProgressCounter* progress = nullptr;
};

// Where the emitted power of a physical map's pass went, summed over all photons
// (double, per channel): emitted = escaped + absorbed + lost at the bounce cap, in
// expectation, and exactly when every surface's sample weight is <= 1 with survival 1 (glass).
struct PhotonTally {
  glm::dvec3 emitted{0.0}, escaped{0.0}, absorbed{0.0}, capped{0.0};
  PerMap<glm::dvec3> stored;  // power of the photons stored, per map
  PhotonTally& operator+=(const PhotonTally& o);
};

// What the emitters stored, per map: its photons in batch order, unmerged (the map
// build sorts straight out of the batches), the prefix cuts of options.prefixBudgets
// and the photons emitted. Each emitter fills only its own kinds.
struct EmittedPhotons {
  MapSlots<PhotonBatches> batches;
  PerMap<PrefixCuts> cuts;
  MapCounts emitted;
  PerMap<PhotonTally> tally;  // the physical maps' (tallies cover the full emission)
  // Converts stored indirect flux back into photon colour (a white light's photons -> 1):
  // emitted photons / (4 pi x summed luminous intensity). Used by the classic estimator.
  float classicScale = 1.0f;
};

// The classic pass: the shadow and indirect maps into `out`. Splits each budget
// across point lights by luminous intensity (largest remainder, so the counts add up
// exactly). The result is identical for any thread count: the maps read the batches
// in batch order.
void emitPhotons(const Scene& scene, const TraceScene& tracer, const EmitOptions& options, EmittedPhotons& out);
inline EmittedPhotons emitPhotons(const Scene& scene, const TraceScene& tracer, const EmitOptions& options) {
  EmittedPhotons out;
  emitPhotons(scene, tracer, options, out);
  return out;
}

// The scene's own photons.* budgets.
inline MapCounts budgetsOf(const Scene& scene) {
  const PhotonSettings& ps = scene.photons;
  MapCounts b;
  b[MapKind::Shadow] = ps.shadowPhotons;
  b[MapKind::Indirect] = ps.indirectPhotons;
  b[MapKind::Global] = ps.globalPhotons;
  b[MapKind::Caustic] = ps.causticPhotons;
  // No volume photons without a medium: that scene runs none of the media work.
  b[MapKind::Volume] = scene.hasMedia() ? ps.volumePhotons : 0;
  return b;
}

// Photons per light for a budget, proportional to each point light's power.
// With `reach` (emit/light_reach.h), by power times reach: the indirect map's split.
std::vector<uint64_t> splitBudget(const Scene& scene, uint64_t total, const std::vector<float>& reach = {});

}  // namespace penumbra
