// The pilot runs the same emit code as the render (same streams, same caps), so
// its store rate is the render's up to sampling noise: one map at a time, each
// with at most kPilotPhotons emitted.
#include "plan/photon_pilot.h"
#include "emit/emit.h"
#include "emit/emit_physical.h"
#include <algorithm>

namespace penumbra {
namespace {

// 4096 paths give the mean stores per path to ~2% (1 sigma) even for geometric
// path lengths (sd ~ mean); 15% covers that with room for the tail of the batches.
constexpr double kPilotMargin = 1.15;

double rate(size_t stored, uint64_t emitted) {
  return emitted > 0 ? double(stored) / double(emitted) : 0.0;
}

}  // namespace

StoreRates measureStoreRates(const Scene& scene, const TraceScene& tracer, const PhotonPlan& plan,
                             const StoreRates& bound) {
  StoreRates r = bound;
  r.measured = true;
  auto margin = [](double measured, double cap) { return std::min(cap, measured * kPilotMargin); };
  using K = MapKind;
  const MapCounts& n = plan.emitted;
  // The pilot's options for one emitter's two maps: at most kPilotPhotons each.
  auto pilotOf = [&](K a, K b) {
    EmitOptions options;
    options.budgets = MapCounts();
    for (K k : {a, b}) {
      (*options.budgets)[k] = std::min(n[k], kPilotPhotons);
      options.maps[k] = n[k] > 0;
    }
    return options;
  };
  auto measure = [&](K k, size_t stored, uint64_t emitted) {
    if (n[k] > 0) r.perPhoton[k] = margin(rate(stored, emitted), bound.perPhoton[k]);
  };
  if (n[K::Shadow] > 0 || n[K::Indirect] > 0) {
    const PhotonMaps maps = emitPhotons(scene, tracer, pilotOf(K::Shadow, K::Indirect));
    measure(K::Shadow, maps.shadow.size(), maps.emitted[K::Shadow]);
    measure(K::Indirect, maps.indirect.size(), maps.emitted[K::Indirect]);
  }
  if (n[K::Global] > 0 || n[K::Caustic] > 0) {
    const PhysicalPhotons photons = emitPhysicalPhotons(scene, tracer, 0, pilotOf(K::Global, K::Caustic));
    measure(K::Global, photons.global.size(), photons.emitted[K::Global]);
    measure(K::Caustic, photons.caustic.size(), photons.emitted[K::Caustic]);
  }
  return r;
}

}  // namespace penumbra
