// The physical model's photon pass: photons carry flux from each light's total
// power, scatter by sampling the BSDF, survive Russian roulette by its albedo, and
// land in a caustic map (L S+ D) or a global map (after >= 1 diffuse bounce).
#pragma once
#include "core/photon.h"
#include "core/scene.h"
#include "emit/emit.h"
#include "geometry/trace_scene.h"

namespace penumbra {

// Where the emitted power went, summed over all photons (double, per channel):
// emitted = escaped + absorbed + lost at the bounce cap, in expectation, and
// exactly when every surface's sample weight is <= 1 with survival 1 (glass).
struct PhotonTally {
  glm::dvec3 emitted{0.0}, escaped{0.0}, absorbed{0.0}, capped{0.0};
  PerMap<glm::dvec3> stored;  // power of the photons stored, caustic and global
  PhotonTally& operator+=(const PhotonTally& o);
};

struct PhysicalPhotons {
  PhotonBatches<IndirectPhoton> caustic, global;
  MapCounts emitted;  // global and caustic
  PhotonTally causticTally, globalTally;
  PrefixCuts causticCuts, globalCuts;  // options.prefixBudgets (tallies cover the full emission)
};

// Pass `pass` of a progressive render draws from its own random streams, so
// passes are independent estimates. Identical for any thread count.
PhysicalPhotons emitPhysicalPhotons(const Scene& scene, const TraceScene& tracer, uint64_t pass = 0,
                                    const EmitOptions& options = {});

// A bounding sphere of the geometry whose BSDF has a delta lobe (mirrors, glass):
// the caustic pass aims its photons at these.
std::vector<SceneSphere> specularTargets(const Scene& scene);

// The global (caustic = false) or caustic pass's photons per light for `total`, as
// emitPhysicalPhotons splits them given options.reach[MapKind::Global / Caustic] = `reach`.
std::vector<uint64_t> splitPhysicalBudget(const Scene& scene, const TraceScene& tracer, bool caustic,
                                          uint64_t total, const std::vector<float>& reach = {});

}  // namespace penumbra
