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
  auto pilot = [&](K k) { return std::min(n[k], kPilotPhotons); };
  auto measure = [&](K k, size_t stored, uint64_t emitted) {
    if (n[k] > 0) r.perPhoton[k] = margin(rate(stored, emitted), bound.perPhoton[k]);
  };
  if (n[K::Shadow] > 0 || n[K::Indirect] > 0) {
    EmitOptions options;
    options.budgets = MapCounts();
    (*options.budgets)[K::Shadow] = pilot(K::Shadow);
    (*options.budgets)[K::Indirect] = pilot(K::Indirect);
    options.maps[K::Shadow] = n[K::Shadow] > 0;
    options.maps[K::Indirect] = n[K::Indirect] > 0;
    PhotonMaps maps = emitPhotons(scene, tracer, options);
    measure(K::Shadow, maps.shadow.size(), maps.emitted[K::Shadow]);
    measure(K::Indirect, maps.indirect.size(), maps.emitted[K::Indirect]);
  }
  if (n[K::Global] > 0 || n[K::Caustic] > 0) {
    EmitOptions options;
    options.budgets = MapCounts();
    (*options.budgets)[K::Global] = pilot(K::Global);
    (*options.budgets)[K::Caustic] = pilot(K::Caustic);
    options.maps[K::Global] = n[K::Global] > 0;
    options.maps[K::Caustic] = n[K::Caustic] > 0;
    PhysicalPhotons photons = emitPhysicalPhotons(scene, tracer, 0, options);
    measure(K::Global, photons.global.size(), photons.emitted[K::Global]);
    measure(K::Caustic, photons.caustic.size(), photons.emitted[K::Caustic]);
  }
  return r;
}

}  // namespace penumbra
