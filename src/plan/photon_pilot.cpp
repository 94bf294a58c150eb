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
  // Every map the plan emits, at most kPilotPhotons each; each emitter reads its own maps.
  EmitOptions options;
  for (K k : kAllMaps) {
    options.budgets[k] = std::min(n[k], kPilotPhotons);
    options.maps[k] = n[k] > 0;
  }
  EmittedPhotons photons;
  if (n[K::Shadow] > 0 || n[K::Indirect] > 0) emitPhotons(scene, tracer, options, photons);
  if (n[K::Global] > 0 || n[K::Caustic] > 0 || n[K::Volume] > 0) emitPhysicalPhotons(scene, tracer, 0, options, photons);
  photons.batches.forEach([&](MapKind k, const auto& stored) {
    if (n[k] > 0) r.perPhoton[k] = margin(rate(stored.size(), photons.emitted[k]), bound.perPhoton[k]);
  });
  return r;
}

}  // namespace penumbra
