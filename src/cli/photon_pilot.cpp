// The pilot runs the same emit code as the render (same streams, same caps), so
// its store rate is the render's up to sampling noise: one map at a time, each
// with kPilotPhotons emitted, then the counts go back to what the scene asked for.
#include "cli/photon_pilot.h"
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

// Restores the scene's photon settings whatever the emitters throw.
struct SettingsGuard {
  Scene& scene;
  PhotonSettings saved;
  explicit SettingsGuard(Scene& s) : scene(s), saved(s.photons) {}
  ~SettingsGuard() { scene.photons = saved; }
};

}  // namespace

StoreRates measureStoreRates(Scene& scene, const TraceScene& tracer, const PhotonPlan& plan,
                             const StoreRates& bound) {
  StoreRates r = bound;
  r.measured = true;
  SettingsGuard guard(scene);
  PhotonSettings& ps = scene.photons;
  auto margin = [](double measured, double cap) { return std::min(cap, measured * kPilotMargin); };
  if (plan.shadow > 0 || plan.indirect > 0) {
    ps.shadowPhotons = std::min(plan.shadow, kPilotPhotons);
    ps.indirectPhotons = std::min(plan.indirect, kPilotPhotons);
    EmitOptions options;
    options.shadowMap = plan.shadow > 0;
    options.indirectMap = plan.indirect > 0;
    PhotonMaps maps = emitPhotons(scene, tracer, options);
    if (plan.shadow > 0) r.shadow = margin(rate(maps.shadow.size(), maps.emittedShadow), bound.shadow);
    if (plan.indirect > 0) r.indirect = margin(rate(maps.indirect.size(), maps.emittedIndirect), bound.indirect);
  }
  if (plan.global > 0 || plan.caustic > 0) {
    ps.globalPhotons = std::min(plan.global, kPilotPhotons);
    ps.causticPhotons = std::min(plan.caustic, kPilotPhotons);
    EmitOptions options;
    options.globalMap = plan.global > 0;
    options.causticMap = plan.caustic > 0;
    PhysicalPhotons photons = emitPhysicalPhotons(scene, tracer, 0, options);
    if (plan.global > 0) r.global = margin(rate(photons.global.size(), photons.emittedGlobal), bound.global);
    if (plan.caustic > 0) r.caustic = margin(rate(photons.caustic.size(), photons.emittedCaustic), bound.caustic);
  }
  return r;
}

}  // namespace penumbra
