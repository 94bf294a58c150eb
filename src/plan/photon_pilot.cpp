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
  if (plan.shadow > 0 || plan.indirect > 0) {
    EmitOptions options;
    options.budgets = MapBudgets{std::min(plan.shadow, kPilotPhotons), std::min(plan.indirect, kPilotPhotons), 0, 0};
    options.shadowMap = plan.shadow > 0;
    options.indirectMap = plan.indirect > 0;
    PhotonMaps maps = emitPhotons(scene, tracer, options);
    if (plan.shadow > 0) r.shadow = margin(rate(maps.shadow.size(), maps.emittedShadow), bound.shadow);
    if (plan.indirect > 0) r.indirect = margin(rate(maps.indirect.size(), maps.emittedIndirect), bound.indirect);
  }
  if (plan.global > 0 || plan.caustic > 0) {
    EmitOptions options;
    options.budgets = MapBudgets{0, 0, std::min(plan.global, kPilotPhotons), std::min(plan.caustic, kPilotPhotons)};
    options.globalMap = plan.global > 0;
    options.causticMap = plan.caustic > 0;
    PhysicalPhotons photons = emitPhysicalPhotons(scene, tracer, 0, options);
    if (plan.global > 0) r.global = margin(rate(photons.global.size(), photons.emittedGlobal), bound.global);
    if (plan.caustic > 0) r.caustic = margin(rate(photons.caustic.size(), photons.emittedCaustic), bound.caustic);
  }
  return r;
}

}  // namespace penumbra
