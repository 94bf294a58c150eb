// One frame from built photon maps: the context the integrators read, the
// precomputed lookups, and the physical model's progressive passes.
#include "plan/render_frame.h"
#include "plan/transport_model.h"
#include "gather/lookup_cache.h"
#include "gather/radiance_estimate.h"
#include "trace/camera.h"
#include "trace/light_visibility.h"
#include "trace/probe_error.h"
#include "trace/shading.h"
#include "core/error_estimate.h"
#include "io/texture_gen.h"
#include <fmt/format.h>

namespace penumbra {
namespace {

// The built map of a light-map kind the context reads (null: none).
const IndirectPhotonMap* lightMap(const ShadingContext& ctx, MapKind k) {
  switch (k) {
    case MapKind::Indirect: return ctx.indirectMap;
    case MapKind::Global: return ctx.globalMap;
    case MapKind::Caustic: return ctx.causticMap;
    default: return nullptr;
  }
}

// photons.lookup = precomputed: the gate verdicts and the model's indirect estimate
// (IndirectLookup), once per cell, from the maps just built, with the pass's gathers
// (passGathers) for the global map. The estimate keeps its own cells; where the gate
// wants finer ones (a penumbra is narrower than a sparse light map's cells), its
// verdicts get a cache of their own, so the estimate is the same with or without it.
// A null key: build without keeping the parameters.
void buildLookup(const Scene& scene, const TransportModel& model, LookupCache& cache, LookupCache& gateCache,
                 std::optional<LookupCacheParams>* cachedKey, std::optional<LookupCacheParams>* gateKey,
                 double* builtSeconds, ShadingContext& ctx, RenderStats& stats, ProgressPhases* meter,
                 const std::string& phaseName) {
  const PhotonSettings& ps = scene.photons;
  Stopwatch phase;
  const IndirectLookup recipe = model.indirectLookup(ps);
  const IndirectPhotonMap* map = lightMap(ctx, recipe.map);
  const bool gate = ctx.choices.gate && ctx.choices.shadows && ctx.shadowMap;
  if (!gate && !map) return;  // nothing to precompute
  LookupCacheParams params;
  params.gate = gate;
  params.gateParams = gateParamsFor(scene, ctx.choices.integrator->glass);
  if (map) params.indirect = recipe.kind;
  const bool global = recipe.map == MapKind::Global;
  params.k = global ? ctx.globalK : recipe.k;
  params.maxRadius = recipe.maxRadius;
  params.radius = global ? ctx.globalRadius : 0.0f;
  params.cellSize = params.k == 0 ? cacheCellSize(params.radius, recipe.k, ps.lookupCell)
                                  : cacheCellSize(map, params.k, ctx.shadowMap, ps.kShadow, ps.lookupCell);
  LookupCacheParams gateOnly;
  bool split = false;
  if (gate && map) {
    const float gateCell = cacheCellSize(nullptr, 0, ctx.shadowMap, ps.kShadow, ps.lookupCell);
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
    into.build(p.gate ? ctx.shadowMap : nullptr, p.indirect != CachedIndirect::None ? map : nullptr, p);
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

void addStage(const PhotonStage& s, RenderStats& stats) {
  stats.time.emit += s.emitSeconds;
  stats.time.buildMaps += s.buildSeconds;
  stats.emitted += s.emitted;
  stats.stored[MapKind::Shadow] += s.shadow.size();
  stats.stored[MapKind::Indirect] += s.indirect.size();
  stats.stored[MapKind::Caustic] += s.caustic.size();
  stats.stored[MapKind::Global] += s.global.size();
}

// Progressive pass `pass` of a frame (Knaus & Zwicker 2011): each map gathers
// k x passRadiusShare nearest photons, so every point's radius shrinks from its own
// k-nearest one; photons.radius > 0 instead fixes one radius for all points, shrunk
// by the same share. The stats keep the typical radius of the last pass.
void passGathers(const PhotonSettings& ps, uint32_t pass, const PhotonStage& maps, ShadingContext& ctx,
                 RenderStats& stats) {
  if (ps.radius > 0.0f) {
    ctx.causticK = ctx.globalK = 0;
    ctx.causticRadius = ctx.globalRadius = static_cast<float>(ps.radius * std::sqrt(passRadiusShare(pass, ps.alpha)));
    stats.causticRadius = stats.globalRadius = ctx.globalRadius;
    return;
  }
  ctx.causticK = passK(ps.kCaustic, pass, ps.alpha);
  ctx.globalK = passK(ps.kGlobal, pass, ps.alpha);
  ctx.causticRadius = ctx.globalRadius = 0.0f;
  GatherScratch scratch;
  stats.causticRadius = typicalKnnRadius(maps.caustic, ctx.causticK, scratch);
  stats.globalRadius = typicalKnnRadius(maps.global, ctx.globalK, scratch);
}

// "render", or "render 2/4" in pass 2 of 4 progressive passes.
std::string phaseName(const char* phase, int pass, int passes) {
  return passes > 1 ? fmt::format("{} {}/{}", phase, pass + 1, passes) : std::string(phase);
}

}  // namespace

std::unique_ptr<TextureLookup> loadTextures(const Scene& scene) {
  if (scene.textures.empty()) return nullptr;
  std::vector<std::string> paths;
  std::vector<bool> data;
  for (const Texture& t : scene.textures) {
    // Procedural textures are generated once into the cache, then read like files.
    paths.push_back(t.path.rfind("builtin:", 0) == 0 ? builtinTexturePath(t.path) : t.path);
    data.push_back(t.data);
  }
  return std::make_unique<TextureLookup>(paths, data);
}

SceneAssets prepareAssets(const Scene& scene, bool textures) {
  SceneAssets assets;
  Stopwatch clock;
  assets.tracer = std::make_unique<TraceScene>(scene);
  assets.bvhSeconds = clock.seconds();
  if (textures) assets.textures = loadTextures(scene);
  return assets;
}

void renderFrame(const Scene& scene, const SceneAssets& assets, PhotonStage& stage,
                 const FrameOptions& options, RenderResult& result) {
  RenderStats& stats = result.stats;
  const TransportModel& model = transportOf(scene);
  const Aov aov = options.aov;
  ShadingContext ctx{scene, *assets.tracer};
  if (options.choices) ctx.choices = *options.choices;
  const bool precomputed = options.precomputed ? *options.precomputed : scene.photons.lookup == PhotonLookup::Precomputed;
  ctx.textures = assets.textures.get();
  ctx.pixelSpread = CameraRays(scene.camera).pixelSpread();
  ctx.hasGlass = sceneHasGlass(scene);
  ctx.classicScale = stage.classicScale;
  ctx.shadowMap = stage.shadow.size() > 0 ? &stage.shadow : nullptr;
  for (const std::string& n : stage.notes) result.notes.push_back(n);
  if (stage.emitted[MapKind::Indirect] > 0 && stage.indirect.empty()) {
    result.notes.push_back("indirect photons requested but none stored (every p_r and p_t is 0?): "
                           "using the ambient term");
  }
  const bool needsLight = readsLight(aov);
  const bool budgeted = options.budget.any() && needsLight && !options.tracePixel;
  const bool fresh = model.freshPhotonsEachPass();
  // --trace-pixel traces the first sample of the render's own sequence, in one pass.
  // A budget's passes sample as any progressive render does, so its image equals the
  // render with photons.passes set to the passes it ran.
  ctx.passes = static_cast<uint32_t>(budgeted ? kBudgetMaxPasses : model.passes(scene, aov));
  const int passes = options.tracePixel ? 1 : static_cast<int>(ctx.passes);
  const Stopwatch wall;
  const std::function<double()> clock = options.clock ? options.clock : [&wall] { return wall.seconds(); };

  LookupCache cache;
  PhotonStage later;  // the maps of physical passes >= 1 (fresh photons each)
  RenderOptions render;
  render.aov = aov;
  PassSpread spread;
  Image sampleSpread;  // one pass: its samples' standard error per pixel
  if (needsLight && passes == 1 && scene.camera.spp > 1) render.standardError = &sampleSpread;
  int done = 0;
  double passStart = clock();
  for (int pass = 0; pass < passes; ++pass) {
    const PhotonStage* maps = &stage;
    if (pass > 0 && fresh) {
      later = PhotonStage();
      PhotonNeeds needs = options.needs;
      needs.maps[MapKind::Shadow] = false;  // the gate's photons are pass 0's, for every pass
      const std::string name = budgeted ? fmt::format("pass {}", pass + 1) : phaseName("photons", pass, passes);
      Emission e = emitPhotonsFor(scene, *assets.tracer, needs, options.budgets, static_cast<uint32_t>(pass), {},
                                  beginPhase(options.progress, name));
      buildStage(e, e.budgets, true, later, beginPhase(options.progress, phaseName("maps", pass, passes)));
      endPhase(options.progress);
      maps = &later;
    }
    if (pass == 0 || fresh) addStage(*maps, stats);
    ctx.indirectMap = maps->indirect.empty() ? nullptr : &maps->indirect;
    ctx.causticMap = maps->caustic.empty() ? nullptr : &maps->caustic;
    ctx.globalMap = maps->global.empty() ? nullptr : &maps->global;
    ctx.pass = static_cast<uint32_t>(pass);
    if (passes > 1 && fresh) passGathers(scene.photons, ctx.pass, *maps, ctx, stats);
    // Pass 0 keeps its lookups with its maps, for later frames on the same maps; a
    // pass on pass 0's maps reads pass 0's lookups.
    if (needsLight && precomputed && (pass == 0 || fresh)) {
      const std::string lookups = phaseName("lookups", pass, passes);
      if (pass == 0) {
        buildLookup(scene, model, stage.lookup, stage.gateLookup, &stage.lookupKey, &stage.gateLookupKey,
                    &stage.lookupSeconds, ctx, stats, options.progress, lookups);
      } else {
        // The gate's photons are pass 0's for every pass: so are its own cells.
        buildLookup(scene, model, cache, stage.gateLookup, nullptr, &stage.gateLookupKey, nullptr, ctx, stats,
                    options.progress, lookups);
      }
    }
    // A gate with no precomputed verdicts votes over the shadow map's KD-trees, which
    // the photon stage leaves out until a frame reads them.
    if (pass == 0 && needsLight && ctx.choices.gate && ctx.shadowMap && !(ctx.gateLookup && ctx.gateLookup->hasGate()) &&
        !stage.shadow.hasTrees()) {
      Stopwatch trees;
      stage.shadow.buildTrees();
      stats.time.buildMaps += trees.seconds();
    }
    Stopwatch phase;
    if (options.tracePixel) {
      result.rayTree = tracePixel(ctx, options.tracePixel->first, options.tracePixel->second);
      done = 1;
      break;
    }
    render.tiles = beginPhase(options.progress, budgeted ? fmt::format("render {}", pass + 1)
                                                         : phaseName("render", pass, passes));
    Image image = renderImage(ctx, render, stats.rays);
    endPhase(options.progress);
    if (ctx.lookup) stats.cacheLazyCells = ctx.lookup->lazyCells();
    if (passes > 1) spread.add(result.image, image, pass);
    if (pass == 0) result.image = std::move(image);
    else for (size_t i = 0; i < image.pixels.size(); ++i) result.image.pixels[i] += image.pixels[i];
    stats.time.render += phase.seconds();
    done = pass + 1;
    if (options.afterPass) options.afterPass(done, result.image, spread.estimate());
    if (budgeted) {
      const double now = clock();
      const BudgetState state{done, now, now - passStart, spread.estimate().noiseRmse};
      passStart = now;
      if (const char* stop = budgetStop(options.budget, state)) {
        stats.budgetStop = stop;
        break;
      }
    }
  }
  stats.passes = done;
  if (budgeted) stats.budget = describeBudget(options.budget);
  // Progressive passes are independent estimates: their mean is the image.
  if (done > 1) {
    for (Color& c : result.image.pixels) c /= static_cast<float>(done);
  }
  if (needsLight && !options.tracePixel) {
    // One pass of one sample (the pixel centres) has no spread: probes beside it measure
    // its error, at every pixel for the error view; their samples count as render time.
    Image probed;
    const bool probes = done == 1 && !render.standardError;
    Stopwatch probing;
    stats.error = done > 1  ? spread.estimate()
                  : probes ? probeError(ctx, result.image, render.aov, options.errorView ? &probed : nullptr)
                           : sampleError(sampleSpread, scene.camera.spp);
    if (probes) stats.time.render += probing.seconds();
    for (MapKind k : kAllMaps) stats.error.sharedMaps = stats.error.sharedMaps || stats.stored[k] > 0;
    if (options.errorView) {
      result.image = done > 1 ? spread.standardError() : probes ? std::move(probed) : std::move(sampleSpread);
    }
  }
  stats.photonMapBytes = std::max<uint64_t>(stats.photonMapBytes, stage.bytes() + later.bytes());
}

}  // namespace penumbra
