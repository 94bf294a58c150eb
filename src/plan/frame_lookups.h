// The precomputed lookups a frame's pass reads (photons.lookup = precomputed): the
// gate's verdicts and the model's indirect estimate, once per cell of a hash grid.
#pragma once
#include "plan/render_frame.h"
#include "plan/transport_model.h"
#include "gather/lookup_cache/lookup_cache.h"
#include "trace/shading.h"
#include <optional>
#include <string>

namespace penumbra {

// The gate verdicts and the model's indirect estimate (IndirectLookup), once per cell,
// from the maps `ctx` reads, with its gathers for the global map. The estimate keeps
// its own cells; where the gate wants finer ones (a penumbra is narrower than a sparse
// light map's cells), its verdicts get a cache of their own, so the estimate is the
// same with or without it. A cache whose key equals the wanted parameters is kept; a
// null key: build without keeping the parameters. Points ctx.lookup/gateLookup at them.
void buildLookup(const Scene& scene, const TransportModel& model, LookupCache& cache, LookupCache& gateCache,
                 std::optional<LookupCacheParams>* cachedKey, std::optional<LookupCacheParams>* gateKey,
                 double* builtSeconds, ShadingContext& ctx, RenderStats& stats, ProgressPhases* meter,
                 const std::string& phaseName);

}  // namespace penumbra
