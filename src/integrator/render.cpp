// Tiles are scheduled by tbb::parallel_for and write disjoint pixels; every
// sample's random numbers come from (seed, pixel, sample), never from a thread.
#include "integrator/render.h"
#include "core/error.h"
#include "core/rng.h"
#include "integrator/camera.h"
#include "integrator/light_visibility.h"
#include "integrator/physical.h"
#include <tbb/blocked_range.h>
#include <tbb/enumerable_thread_specific.h>
#include <tbb/parallel_for.h>
#include <atomic>
#include <limits>
#include <numeric>

namespace penumbra {

Aov parseAov(const std::string& name) {
  if (name == "beauty") return Aov::Beauty;
  if (name == "depth") return Aov::Depth;
  if (name == "normal") return Aov::Normal;
  if (name == "indirect") return Aov::Indirect;
  if (name == "direct") return Aov::Direct;
  if (name == "caustic") return Aov::Caustic;
  throw InputError("--aov: unknown view '" + name +
                   "' (use beauty, depth, normal, indirect, direct or caustic)");
}

namespace {

// One sample of the chosen view. Depth stores the raw distance (normalised for
// display afterwards), -1 on a miss.
uint8_t physicalTerms(Aov aov) {
  switch (aov) {
    case Aov::Direct: return kTermDirect;
    case Aov::Caustic: return kTermCaustic;
    case Aov::Indirect: return kTermGlobal;
    default: return kTermAll;
  }
}

Color shadeSample(const ShadingContext& ctx, const Ray& ray, Aov aov, ThreadState& ts) {
  ts.raysLeft = kMaxRaysPerSample;
  if (ctx.scene.render.model == ShadingModel::Physical && aov != Aov::Depth && aov != Aov::Normal) {
    return tracePhysical(ctx, ray, 0, Color(1.0f), RayKind::Camera, physicalTerms(aov), -1, ts);
  }
  if (aov == Aov::Beauty) return traceRay(ctx, ray, 0, Color(1.0f), 0.0f, RayKind::Camera, -1, ts);
  ++ts.counts.camera;
  Hit hit;
  if (!ctx.tracer.intersect(ray, hit)) return aov == Aov::Depth ? Color(-1.0f) : Color(0.0f);
  if (aov == Aov::Depth) return Color(hit.t);
  SurfaceRecord s = ctx.tracer.surface(ray, hit, kSurfaceShadingNormal);
  if (aov == Aov::Normal) return s.ns * 0.5f + 0.5f;
  const Material& m = ctx.scene.materials[s.material];
  CachedAnswer storage;  // Aov::Indirect
  return ambientTerm(ctx, s, m, lookupAt(ctx, s, storage, ts), ts);
}

// Depth view as in the report: near black, far white, misses white.
void normaliseDepth(Image& image) {
  float lo = kInf, hi = -kInf;
  for (const Color& c : image.pixels) {
    if (c.r >= 0.0f) { lo = std::min(lo, c.r); hi = std::max(hi, c.r); }
  }
  float range = hi > lo ? hi - lo : 1.0f;
  for (Color& c : image.pixels) {
    c = c.r < 0.0f ? Color(1.0f) : Color(std::isfinite(lo) ? (c.r - lo) / range : 1.0f);
  }
}

}  // namespace

Image renderImage(const ShadingContext& ctx, const RenderOptions& options, RayCounts& counts) {
  const Camera& cam = ctx.scene.camera;
  CameraRays camera(cam);
  Image image(cam.width, cam.height);
  const int tile = options.tileSize;
  const int tilesX = (cam.width + tile - 1) / tile, tilesY = (cam.height + tile - 1) / tile;
  const int numTiles = tilesX * tilesY;
  const uint64_t seed = ctx.scene.render.seed;
  tbb::enumerable_thread_specific<ThreadState> states;
  std::atomic<int> tilesDone{0};

  tbb::parallel_for(tbb::blocked_range<int>(0, numTiles, 1), [&](const tbb::blocked_range<int>& r) {
    ThreadState& ts = states.local();
    for (int t = r.begin(); t != r.end(); ++t) {
      int x0 = (t % tilesX) * tile, y0 = (t / tilesX) * tile;
      int x1 = std::min(x0 + tile, cam.width), y1 = std::min(y0 + tile, cam.height);
      for (int y = y0; y < y1; ++y) {
        for (int x = x0; x < x1; ++x) {
          uint64_t pixel = static_cast<uint64_t>(y) * cam.width + x;
          glm::dvec3 sum(0.0);  // double: many finite samples near float's top cannot overflow
          int counted = 0;
          // A progressive pass continues the sample sequence where earlier passes stopped.
          const uint64_t first = static_cast<uint64_t>(ctx.pass) * cam.spp;
          for (int s = 0; s < cam.spp; ++s) {
            Rng rng(hashKey(seed, pixel, first + static_cast<uint64_t>(s)));
            Vec2 off = stratified2D(s, cam.spp, rng);
            beginSample(ts, hashKey(seed, pixel, first + static_cast<uint64_t>(s)));
            Color c = shadeSample(ctx, camera.generate(x + off.x, y + off.y), options.aov, ts);
            // A NaN or Inf sample would poison the pixel (or be written as 0 and hide):
            // drop it, count it, and let the pixel's other samples stand.
            if (!isFinite(c)) {
              ++ts.counts.nonfiniteSamples;
              continue;
            }
            // Depth averages only the samples that hit: a miss is "no depth", not -1 m.
            if (options.aov == Aov::Depth && c.r < 0.0f) continue;
            sum += glm::dvec3(c);
            ++counted;
          }
          // A mean above float range is clamped to it (the writer clamps further).
          const double top = std::numeric_limits<float>::max();
          image.at(x, y) = counted > 0 ? Color(glm::min(sum / double(counted), glm::dvec3(top)))
                           : options.aov == Aov::Depth ? Color(-1.0f) : Color(0.0f);
        }
      }
      int done = ++tilesDone;
      if (options.progress) options.progress(static_cast<double>(done) / numTiles);
    }
  });

  for (const ThreadState& ts : states) counts += ts.counts;
  if (options.aov == Aov::Depth) normaliseDepth(image);
  return image;
}

void checkPixel(const Camera& cam, int x, int y) {
  if (x < 0 || y < 0 || x >= cam.width || y >= cam.height) {
    throw InputError("--trace-pixel: " + std::to_string(x) + "," + std::to_string(y) +
                     " is outside the " + std::to_string(cam.width) + "x" + std::to_string(cam.height) +
                     " image");
  }
}

RayTree tracePixel(const ShadingContext& ctx, int x, int y) {
  const Camera& cam = ctx.scene.camera;
  checkPixel(cam, x, y);
  RayTree tree;
  ThreadState ts;
  ts.recorder = &tree;
  uint64_t pixel = static_cast<uint64_t>(y) * cam.width + x;
  Rng rng(hashKey(ctx.scene.render.seed, pixel, 0));
  Vec2 off = stratified2D(0, cam.spp, rng);
  beginSample(ts, hashKey(ctx.scene.render.seed, pixel, 0));
  CameraRays camera(cam);
  Ray ray = camera.generate(x + off.x, y + off.y);
  if (ctx.scene.render.model == ShadingModel::Physical) {
    tracePhysical(ctx, ray, 0, Color(1.0f), RayKind::Camera, kTermAll, -1, ts);
  } else {
    traceRay(ctx, ray, 0, Color(1.0f), 0.0f, RayKind::Camera, -1, ts);
  }
  return tree;
}

}  // namespace penumbra
