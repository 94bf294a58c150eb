// The physical model's photon pass: photons carry flux from each light's total
// power, scatter by sampling the BSDF, survive Russian roulette by its albedo, and
// land in a caustic map (L S+ D) or a global map (after >= 1 diffuse bounce).
#pragma once
#include "core/photon.h"
#include "core/scene.h"
#include "emit/emit.h"
#include "geometry/trace_scene.h"

namespace penumbra {

// The global and caustic maps (and in a scene with a medium the volume map), their
// tallies and cuts, into `out`. Pass `pass` of a
// progressive render draws from its own random streams, so passes are independent
// estimates. Identical for any thread count.
void emitPhysicalPhotons(const Scene& scene, const TraceScene& tracer, uint64_t pass, const EmitOptions& options,
                         EmittedPhotons& out);
inline EmittedPhotons emitPhysicalPhotons(const Scene& scene, const TraceScene& tracer, uint64_t pass,
                                          const EmitOptions& options) {
  EmittedPhotons out;
  emitPhysicalPhotons(scene, tracer, pass, options, out);
  return out;
}

// A bounding sphere of the geometry whose BSDF has a delta lobe (mirrors, glass):
// the caustic pass aims its photons at these.
std::vector<SceneSphere> specularTargets(const Scene& scene);

// The global (caustic = false) or caustic pass's photons per light for `total`, as
// emitPhysicalPhotons splits them given options.reach[MapKind::Global / Caustic] = `reach`.
std::vector<uint64_t> splitPhysicalBudget(const Scene& scene, const TraceScene& tracer, bool caustic,
                                          uint64_t total, const std::vector<float>& reach = {});

}  // namespace penumbra
