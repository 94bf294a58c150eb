// Which caches a pass's lookups need, built only when their parameters changed.
#include "plan/frame_lookups.h"
#include "trace/light_visibility.h"

namespace penumbra {
void buildLookup(const Scene& scene, const TransportModel& model, LookupCache& cache, LookupCache& gateCache,
                 std::optional<LookupCacheParams>* cachedKey, std::optional<LookupCacheParams>* gateKey,
                 double* builtSeconds, ShadingContext& ctx, RenderStats& stats, ProgressPhases* meter,
                 const std::string& phaseName) {
  const PhotonSettings& ps = scene.photons;
  Stopwatch phase;
  const IndirectLookup recipe = model.indirectLookup(ps);
  const IndirectPhotonMap* map = *ctx.maps.light(recipe.map);
  const ShadowPhotonMap* shadowMap = ctx.maps.get<MapKind::Shadow>();
  const bool gate = ctx.choices.gate && ctx.choices.shadows && shadowMap;
  if (!gate && !map) return;  // nothing to precompute
  LookupCacheParams params;
  params.gate = gate;
  params.gateParams = gateParamsFor(scene, ctx.choices.integrator->glass);
  if (map) params.indirect = recipe.kind;
  const bool global = recipe.map == MapKind::Global;
  params.k = global ? ctx.gathers[MapKind::Global].k : recipe.k;
  params.maxRadius = recipe.maxRadius;
  params.radius = global ? ctx.gathers[MapKind::Global].maxRadius : 0.0f;
  params.cellSize = params.k == 0 ? cacheCellSize(params.radius, recipe.k, ps.lookupCell)
                                  : cacheCellSize(map, params.k, shadowMap, ps.kShadow, ps.lookupCell);
  LookupCacheParams gateOnly;
  bool split = false;
  if (gate && map) {
    const float gateCell = cacheCellSize(nullptr, 0, shadowMap, ps.kShadow, ps.lookupCell);
    if (gateCell > 0.0f && (!(params.cellSize > 0.0f) || gateCell < params.cellSize)) {
      split = params.cellSize > 0.0f;
      gateOnly = params;
      gateOnly.indirect = CachedIndirect::None;
      gateOnly.cellSize = gateCell;
      if (split) params.gate = false;
      else params.cellSize = gateCell;
    }
  }
  const bool fresh = !(cachedKey && *cachedKey && sameLookup(**cachedKey, params));
  const bool freshGate = split && !(gateKey && *gateKey && sameLookup(**gateKey, gateOnly));
  ProgressCounter* progress = fresh || freshGate ? beginPhase(meter, phaseName) : nullptr;
  auto build = [&](const LookupCacheParams& wanted, LookupCache& into, std::optional<LookupCacheParams>* key) {
    if (key) key->reset();  // a build that throws leaves no key to a half-built cache
    LookupCacheParams p = wanted;
    p.progress = progress;
    into.build(p.gate ? shadowMap : nullptr, p.indirect != CachedIndirect::None ? map : nullptr, p);
    if (key) *key = wanted;
  };
  if (fresh) build(params, cache, cachedKey);
  if (freshGate) build(gateOnly, gateCache, gateKey);
  if (fresh || freshGate) endPhase(meter);
  if (builtSeconds && (fresh || freshGate)) *builtSeconds = phase.seconds();
  ctx.lookup = cache.empty() ? nullptr : &cache;
  ctx.gateLookup = split ? (gateCache.empty() ? nullptr : &gateCache) : ctx.lookup;
  if (!ctx.lookup) ctx.lookup = ctx.gateLookup;
  stats.time.precompute += phase.seconds();
  const LookupCache* g = ctx.gateLookup ? ctx.gateLookup : ctx.lookup;
  stats.cacheRecords = cache.records() + (split ? gateCache.records() : 0);
  stats.cacheSplits = g ? g->splitLines() : 0;
  stats.cacheCell = g ? g->cellSize() : cache.cellSize();
  stats.cacheBytes = cache.memoryBytes() + (split ? gateCache.memoryBytes() : 0);
}

}  // namespace penumbra
