// One render from scene file to image: load, build the BVH, emit photons,
// build both photon maps concurrently, trace tiles, write the image.
#include "cli/pipeline.h"
#include "emit/emit.h"
#include "gather/photon_map.h"
#include "io/image_io.h"
#include "io/scene_loader.h"
#include "io/texture_gen.h"
#include "integrator/camera.h"
#include "integrator/render.h"
#include "integrator/texture_lookup.h"
#include <tbb/global_control.h>
#include <tbb/info.h>
#include <tbb/parallel_invoke.h>
#include <fmt/format.h>
#include <memory>

namespace penumbra {
namespace {

ImageMetadata describe(const Scene& scene, const RenderStats& stats, const std::string& aov) {
  const auto& ps = scene.photons;
  return {{"penumbra:scene", scene.name},
          {"penumbra:scene_file", scene.file},
          {"penumbra:aov", aov},
          {"penumbra:settings",
           fmt::format("{}x{} spp={} max_depth={} seed={} shadow_photons={} indirect_photons={} "
                       "k_shadow={} k_indirect={} gate={} estimator={}",
                       scene.camera.width, scene.camera.height, scene.camera.spp, scene.render.maxDepth,
                       scene.render.seed, stats.emittedShadow, stats.emittedIndirect, ps.kShadow,
                       ps.kIndirect, ps.gate ? "on" : "off",
                       ps.estimator == IndirectEstimator::Classic ? "classic" : "density")}};
}

bool hasPointLight(const Scene& scene) {
  for (const Light& l : scene.lights) {
    if (l.type == LightType::Point) return true;
  }
  return false;
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
  const std::string aovName = request.aov.empty() ? scene.render.aov : request.aov;
  Aov aov = parseAov(aovName);
  // Bad output paths and pixels fail now, not after minutes of photons and tiles.
  if (!request.outputPath.empty() && !request.tracePixel) checkImageOutputPath(request.outputPath);
  if (request.tracePixel) checkPixel(scene.camera, request.tracePixel->first, request.tracePixel->second);

  phase = Stopwatch();
  TraceScene tracer(scene);
  stats.time.buildBvh = phase.seconds();

  // Photon maps only exist for point lights; the beauty and indirect views use them.
  bool wantPhotons = aov == Aov::Beauty || aov == Aov::Indirect;
  ShadowPhotonMap shadowMap;
  IndirectPhotonMap indirectMap;
  float classicScale = 1.0f;
  if (wantPhotons && hasPointLight(scene)) {
    if (request.progress) request.progress("photons", 0.0);
    phase = Stopwatch();
    EmitOptions emitOptions;
    emitOptions.shadowMap = aov == Aov::Beauty;
    PhotonMaps maps = emitPhotons(scene, tracer, emitOptions);
    stats.time.emit = phase.seconds();
    stats.emittedShadow = maps.emittedShadow;
    stats.emittedIndirect = maps.emittedIndirect;
    stats.storedShadow = maps.shadow.size();
    stats.storedIndirect = maps.indirect.size();
    classicScale = maps.classicScale;
    if (request.progress) request.progress("maps", 0.0);
    phase = Stopwatch();
    // nanoflann builds single-threaded: build the two trees side by side.
    tbb::parallel_invoke([&] { shadowMap.build(std::move(maps.shadow), scene.lights.size()); },
                         [&] { indirectMap.build(std::move(maps.indirect)); });
    stats.time.buildMaps = phase.seconds();
    stats.photonMapBytes = shadowMap.memoryBytes() + indirectMap.memoryBytes();
    if (scene.photons.indirectPhotons > 0 && indirectMap.empty()) {
      result.notes.push_back("indirect photons requested but none stored (every p_r and p_t is 0?): "
                             "using the ambient term");
    }
  } else if (wantPhotons && !scene.lights.empty()) {
    result.notes.push_back("only directional lights: rendering without photon maps");
  }

  std::unique_ptr<TextureLookup> textures;
  if (!scene.textures.empty()) {
    std::vector<std::string> paths;
    for (const Texture& t : scene.textures) {
      // Procedural textures are generated once into the cache, then read like files.
      paths.push_back(t.path.rfind("builtin:", 0) == 0 ? builtinTexturePath(t.path) : t.path);
    }
    textures = std::make_unique<TextureLookup>(paths);
  }

  ShadingContext ctx{scene, tracer};
  ctx.shadowMap = shadowMap.size() > 0 ? &shadowMap : nullptr;
  ctx.indirectMap = indirectMap.empty() ? nullptr : &indirectMap;
  ctx.textures = textures.get();
  ctx.classicScale = classicScale;
  ctx.pixelSpread = CameraRays(scene.camera).pixelSpread();
  ctx.hasGlass = sceneHasGlass(scene);

  stats.scene = scene.name;
  stats.width = scene.camera.width;
  stats.height = scene.camera.height;
  stats.spp = scene.camera.spp;
  stats.threads = threads;
  stats.seed = scene.render.seed;

  phase = Stopwatch();
  if (request.tracePixel) {
    result.rayTree = tracePixel(ctx, request.tracePixel->first, request.tracePixel->second);
  } else {
    RenderOptions options;
    options.aov = aov;
    if (request.progress) options.progress = [&](double f) { request.progress("render", f); };
    result.image = renderImage(ctx, options, stats.rays);
  }
  stats.time.render = phase.seconds();

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
