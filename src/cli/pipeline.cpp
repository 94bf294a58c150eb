// One render from scene file to image: load, build the BVH, emit photons,
// build both photon maps concurrently, trace tiles, write the image.
#include "cli/pipeline.h"
#include "cli/gate_decision.h"
#include "cli/job_admission.h"
#include "core/error.h"
#include "emit/emit.h"
#include "emit/emit_physical.h"
#include "gather/lookup_cache.h"
#include "gather/photon_map.h"
#include "gather/radiance_estimate.h"
#include "io/image_io.h"
#include "io/scene_loader.h"
#include "io/texture_gen.h"
#include "integrator/camera.h"
#include "integrator/light_visibility.h"
#include "integrator/render.h"
#include "integrator/texture_lookup.h"
#include "integrator/shading.h"
#include <tbb/global_control.h>
#include <tbb/info.h>
#include <tbb/parallel_invoke.h>
#include <fmt/format.h>
#include <memory>

namespace penumbra {
namespace {

ImageMetadata describe(const Scene& scene, const RenderStats& stats, const std::string& aov) {
  const auto& ps = scene.photons;
  bool physical = scene.render.model == ShadingModel::Physical;
  std::string photons =
      physical ? fmt::format("global_photons={} caustic_photons={} k_global={} k_caustic={} "
                             "passes={} alpha={} radius={} max_bounces={} shadow_photons={} "
                             "k_shadow={} gate={}",
                             ps.globalPhotons, ps.causticPhotons, ps.kGlobal, ps.kCaustic, ps.passes,
                             ps.alpha, ps.radius, ps.maxBounces, stats.emittedShadow, ps.kShadow,
                             ps.gate ? "on" : "off")
               : fmt::format("shadow_photons={} indirect_photons={} k_shadow={} k_indirect={} "
                             "max_radius={} max_bounces={} sampling={} gate={} estimator={}",
                             stats.emittedShadow, stats.emittedIndirect, ps.kShadow, ps.kIndirect,
                             ps.maxRadius, ps.maxBounces,
                             ps.sampling == HemisphereSampling::Cosine ? "cosine" : "uniform",
                             ps.gate ? "on" : "off",
                             ps.estimator == IndirectEstimator::Classic ? "classic" : "density");
  photons += ps.lookup == PhotonLookup::Precomputed
                 ? fmt::format(" lookup=precomputed lookup_cell={}", ps.lookupCell)
                 : std::string(" lookup=exact");
  return {{"penumbra:scene", scene.name},
          {"penumbra:scene_file", scene.file},
          {"penumbra:aov", aov},
          {"penumbra:model", physical ? "physical" : "classic"},
          {"penumbra:settings", fmt::format("{}x{} spp={} max_depth={} seed={} {}", scene.camera.width,
                                            scene.camera.height, scene.camera.spp,
                                            scene.render.maxDepth, scene.render.seed, photons)}};
}

// The classic photon passes (and every gate) emit from point and area lights.
bool hasPhotonLight(const Scene& scene) {
  for (const Light& l : scene.lights) {
    if (l.type != LightType::Directional) return true;
  }
  return false;
}

void reportProgress(const RenderRequest& request, const char* phase, double fraction) {
  if (request.progress) request.progress(phase, fraction);
}

// Everything a render reads besides the scene; owned here so the context can point in.
struct Maps {
  ShadowPhotonMap shadow;
  IndirectPhotonMap indirect, caustic, global;
  LookupCache lookup;
  size_t bytes() const {
    return shadow.memoryBytes() + indirect.memoryBytes() + caustic.memoryBytes() + global.memoryBytes();
  }
};

// photons.lookup = precomputed: the gate verdicts and the indirect (classic) or global
// (physical) estimate, once per cell, from the maps just built. `radius` > 0 is the
// physical pass's fixed gather radius.
void buildLookup(const Scene& scene, Maps& maps, ShadingContext& ctx, float radius,
                 RenderStats& stats) {
  const PhotonSettings& ps = scene.photons;
  if (ps.lookup != PhotonLookup::Precomputed) return;
  Stopwatch phase;
  const bool physical = scene.render.model == ShadingModel::Physical;
  const IndirectPhotonMap* map = physical ? ctx.globalMap : ctx.indirectMap;
  LookupCacheParams params;
  params.gate = ps.gate && scene.render.shadows && ctx.shadowMap;
  params.gateParams = gateParamsFor(scene);
  if (map) {
    params.indirect = physical ? CachedIndirect::Irradiance
                      : ps.estimator == IndirectEstimator::Density ? CachedIndirect::Density
                                                                   : CachedIndirect::Classic;
  }
  params.k = physical ? ps.kGlobal : ps.kIndirect;
  params.maxRadius = physical ? 0.0f : ps.maxRadius;
  params.radius = physical ? radius : 0.0f;
  params.cellSize = radius > 0.0f ? cacheCellSize(radius, params.k, ps.lookupCell)
                                  : cacheCellSize(map, params.k, ctx.shadowMap, ps.kShadow, ps.lookupCell);
  maps.lookup.build(params.gate ? ctx.shadowMap : nullptr, map, params);
  ctx.lookup = maps.lookup.empty() ? nullptr : &maps.lookup;
  stats.time.precompute += phase.seconds();
  stats.cacheRecords = maps.lookup.records();
  stats.cacheCell = maps.lookup.cellSize();
  stats.cacheBytes = maps.lookup.memoryBytes();
}

// Classic model: the shadow map (gate) and the indirect map, once.
void buildClassicMaps(const Scene& scene, const TraceScene& tracer, Aov aov,
                      const RenderRequest& request, Maps& maps, ShadingContext& ctx,
                      RenderResult& result) {
  RenderStats& stats = result.stats;
  bool wantPhotons = aov == Aov::Beauty || aov == Aov::Indirect;
  if (!wantPhotons) return;
  if (!hasPhotonLight(scene)) {
    if (!scene.lights.empty()) result.notes.push_back("only directional lights: rendering without photon maps");
    return;
  }
  reportProgress(request, "photons", 0.0);
  Stopwatch phase;
  EmitOptions emitOptions;
  emitOptions.shadowMap = aov == Aov::Beauty;
  PhotonMaps emitted = emitPhotons(scene, tracer, emitOptions);
  stats.time.emit = phase.seconds();
  stats.emittedShadow = emitted.emittedShadow;
  stats.emittedIndirect = emitted.emittedIndirect;
  stats.storedShadow = emitted.shadow.size();
  stats.storedIndirect = emitted.indirect.size();
  ctx.classicScale = emitted.classicScale;
  reportProgress(request, "maps", 0.0);
  phase = Stopwatch();
  // nanoflann builds single-threaded: build the two trees side by side.
  tbb::parallel_invoke([&] { maps.shadow.build(std::move(emitted.shadow), scene.lights.size()); },
                       [&] { maps.indirect.build(std::move(emitted.indirect)); });
  stats.time.buildMaps = phase.seconds();
  if (scene.photons.indirectPhotons > 0 && maps.indirect.empty()) {
    result.notes.push_back("indirect photons requested but none stored (every p_r and p_t is 0?): "
                           "using the ambient term");
  }
  ctx.shadowMap = maps.shadow.size() > 0 ? &maps.shadow : nullptr;
  ctx.indirectMap = maps.indirect.empty() ? nullptr : &maps.indirect;
  buildLookup(scene, maps, ctx, 0.0f, stats);
}

// Physical model, one progressive pass: fresh caustic and global photons (pass-keyed
// streams), their maps, and the pass's gather radii (Knaus & Zwicker 2011:
// r_{i+1}^2 = r_i^2 (i + alpha) / (i + 1), so the average of the passes converges).
void buildPhysicalPass(const Scene& scene, const TraceScene& tracer, uint32_t pass, Aov aov,
                       Maps& maps, ShadingContext& ctx, RenderStats& stats) {
  const PhotonSettings& ps = scene.photons;
  EmitOptions options;  // only the maps this view reads
  options.globalMap = aov == Aov::Beauty || aov == Aov::Indirect;
  options.causticMap = aov == Aov::Beauty || aov == Aov::Caustic;
  Stopwatch phase;
  PhysicalPhotons photons = emitPhysicalPhotons(scene, tracer, pass, options);
  stats.time.emit += phase.seconds();
  stats.emittedCaustic += photons.emittedCaustic;
  stats.emittedGlobal += photons.emittedGlobal;
  stats.storedCaustic += photons.caustic.size();
  stats.storedGlobal += photons.global.size();
  phase = Stopwatch();
  tbb::parallel_invoke([&] { maps.caustic.build(std::move(photons.caustic)); },
                       [&] { maps.global.build(std::move(photons.global)); });
  stats.time.buildMaps += phase.seconds();
  ctx.causticMap = maps.caustic.empty() ? nullptr : &maps.caustic;
  ctx.globalMap = maps.global.empty() ? nullptr : &maps.global;
  ctx.pass = pass;
  if (ps.passes <= 1) {  // a single pass gathers the k nearest
    buildLookup(scene, maps, ctx, 0.0f, stats);
    return;
  }
  // A radius still 0 (first pass, or every earlier pass stored nothing) starts from
  // this pass's photons; afterwards it only shrinks.
  auto step = [&](float& r, const IndirectPhotonMap& map, int k) {
    if (r > 0.0f) {
      r *= std::sqrt((pass + ps.alpha) / (pass + 1.0f));
    } else {
      GatherScratch scratch;
      r = ps.radius > 0.0f ? ps.radius : typicalKnnRadius(map, k, scratch);
    }
  };
  step(ctx.causticRadius, maps.caustic, ps.kCaustic);
  step(ctx.globalRadius, maps.global, ps.kGlobal);
  stats.causticRadius = ctx.causticRadius;
  stats.globalRadius = ctx.globalRadius;
  buildLookup(scene, maps, ctx, ctx.globalRadius, stats);
}

// The physical model's gate reads shadow photons; they do not change between passes.
void buildPhysicalGate(const Scene& scene, const TraceScene& tracer, Aov aov, Maps& maps,
                       ShadingContext& ctx, RenderStats& stats) {
  if (!scene.photons.gate || !scene.render.shadows || !hasPhotonLight(scene)) return;
  if (aov != Aov::Beauty && aov != Aov::Direct) return;
  Stopwatch phase;
  EmitOptions options;
  options.indirectMap = false;
  PhotonMaps emitted = emitPhotons(scene, tracer, options);
  stats.time.emit += phase.seconds();
  stats.emittedShadow = emitted.emittedShadow;
  stats.storedShadow = emitted.shadow.size();
  phase = Stopwatch();
  maps.shadow.build(std::move(emitted.shadow), scene.lights.size());
  stats.time.buildMaps += phase.seconds();
  ctx.shadowMap = maps.shadow.size() > 0 ? &maps.shadow : nullptr;
}

std::unique_ptr<TextureLookup> loadTextures(const Scene& scene) {
  if (scene.textures.empty()) return nullptr;
  std::vector<std::string> paths;
  for (const Texture& t : scene.textures) {
    // Procedural textures are generated once into the cache, then read like files.
    paths.push_back(t.path.rfind("builtin:", 0) == 0 ? builtinTexturePath(t.path) : t.path);
  }
  return std::make_unique<TextureLookup>(paths);
}

}  // namespace

RenderResult runRender(const RenderRequest& request) {
  Stopwatch total;
  int threads = request.threads > 0 ? request.threads : tbb::info::default_concurrency();
  tbb::global_control limit(tbb::global_control::max_allowed_parallelism, threads);
  RenderResult result;
  RenderStats& stats = result.stats;

  Stopwatch phase;
  Scene scene = loadScene(request.scenePath, request.overrides);
  stats.time.load = phase.seconds();
  // photons.gate = auto: build the shadow map only where it is estimated to pay.
  const GateMode gateMode = scene.photons.gateMode;
  stats.gateMode = gateMode == GateMode::Auto ? "auto" : gateMode == GateMode::On ? "on" : "off";
  if (gateMode == GateMode::Auto) {
    const GateDecision decision = decideGate(scene);
    scene.photons.gate = decision.gate;
    stats.gateReason = decision.reason;
  }
  stats.gate = scene.photons.gate;
  const std::string aovName = request.aov.empty() ? scene.render.aov : request.aov;
  Aov aov = parseAov(aovName);
  const bool physical = scene.render.model == ShadingModel::Physical;
  if (!physical && (aov == Aov::Direct || aov == Aov::Caustic)) {
    throw InputError(scene.file + ": view '" + aovName +
                     "' needs the physical model (render.model: \"physical\")");
  }
  // Bad pixels, outputs and oversized jobs fail now, not after minutes of photons and tiles.
  if (request.tracePixel) checkPixel(scene.camera, request.tracePixel->first, request.tracePixel->second);
  Admission admission = admitRender(scene, request, aov, threads);

  phase = Stopwatch();
  TraceScene tracer(scene);
  stats.time.buildBvh = phase.seconds();
  confirmRender(admission, scene, tracer, request);
  result.estimate = admission.estimate;
  std::unique_ptr<TextureLookup> textures = loadTextures(scene);

  Maps maps;
  ShadingContext ctx{scene, tracer};
  ctx.textures = textures.get();
  ctx.pixelSpread = CameraRays(scene.camera).pixelSpread();
  ctx.hasGlass = sceneHasGlass(scene);

  stats.scene = scene.name;
  stats.width = scene.camera.width;
  stats.height = scene.camera.height;
  stats.spp = scene.camera.spp;
  stats.threads = threads;
  stats.seed = scene.render.seed;
  stats.model = physical ? "physical" : "classic";
  stats.lookup = scene.photons.lookup == PhotonLookup::Precomputed ? "precomputed" : "exact";
  const bool needsLight = aov != Aov::Depth && aov != Aov::Normal;
  const int passes = physical && needsLight && !request.tracePixel ? scene.photons.passes : 1;
  stats.passes = passes;

  if (!physical) buildClassicMaps(scene, tracer, aov, request, maps, ctx, result);
  else if (needsLight) buildPhysicalGate(scene, tracer, aov, maps, ctx, stats);

  RenderOptions options;
  options.aov = aov;
  for (int pass = 0; pass < passes; ++pass) {
    if (physical && needsLight) {
      reportProgress(request, "photons", static_cast<double>(pass) / passes);
      buildPhysicalPass(scene, tracer, static_cast<uint32_t>(pass), aov, maps, ctx, stats);
    }
    phase = Stopwatch();
    if (request.tracePixel) {
      result.rayTree = tracePixel(ctx, request.tracePixel->first, request.tracePixel->second);
      break;
    }
    if (request.progress) {
      options.progress = [&](double f) { request.progress("render", (pass + f) / passes); };
    }
    Image image = renderImage(ctx, options, stats.rays);
    if (pass == 0) result.image = std::move(image);
    else for (size_t i = 0; i < image.pixels.size(); ++i) result.image.pixels[i] += image.pixels[i];
    stats.time.render += phase.seconds();
  }
  // Progressive passes are independent estimates: their mean is the image.
  if (passes > 1) {
    for (Color& c : result.image.pixels) c /= static_cast<float>(passes);
  }
  stats.photonMapBytes = maps.bytes();

  if (!request.outputPath.empty() && !request.tracePixel) {
    phase = Stopwatch();
    writeImage(request.outputPath, result.image, describe(scene, stats, aovName));
    stats.time.write = phase.seconds();
  }
  stats.time.total = total.seconds();
  stats.peakRssBytes = peakRssBytes();
  return result;
}

}  // namespace penumbra
