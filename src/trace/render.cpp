// Tiles are scheduled by tbb::parallel_for and write disjoint pixels; every
// sample's random numbers come from (seed, pixel, sample), never from a thread.
#include "trace/render.h"
#include "core/error.h"
#include "core/rng.h"
#include "trace/camera.h"
#include "trace/light_visibility.h"
#include <tbb/blocked_range.h>
#include <tbb/enumerable_thread_specific.h>
#include <tbb/parallel_for.h>
#include <atomic>
#include <limits>
#include <numeric>

namespace penumbra {

namespace {

bool geometric(Aov aov) { return aov == Aov::Depth || aov == Aov::Normal; }

// A geometric view's sample that hit nothing: no depth is -2 and no normal has r = -2,
// so the pixel's mean can leave it out and count it against the coverage instead.
constexpr float kNoHit = -2.0f;

// One sample of the chosen view: the transport model's integrator for views that
// read light; here the physical values for depth (distance along the camera ray) and
// normal (world-space shading normal, facing the ray), which writers map for display
// (io/aov_display.h). `hit`: the ray's first hit, already traced (alone or in a
// packet); null on a miss.
Color shadeTraced(const ShadingContext& ctx, const Ray& ray, const Hit* hit, Aov aov, ThreadState& ts) {
  ts.raysLeft = kMaxRaysPerSample;
  if (!geometric(aov)) return ctx.choices.integrator->sample(ctx, ray, hit, aov, ts);
  ++ts.counts.camera;
  if (!hit) return Color(kNoHit);
  if (aov == Aov::Depth) return Color(hit->t);
  return ctx.tracer.surface(ray, *hit, kSurfaceShadingNormal).ns;
}

Color shadeSample(const ShadingContext& ctx, const Ray& ray, Aov aov, ThreadState& ts) {
  Hit hit;
  const bool found = ctx.tracer.intersect(ray, hit);
  return shadeTraced(ctx, ray, found ? &hit : nullptr, aov, ts);
}

// One sample into its pixel's running sum. A NaN or Inf sample would poison the pixel
// (or be written as 0 and hide): drop it, count it, and let the pixel's other samples
// stand. Geometric views average only the samples that hit: a miss is "no depth",
// not 0 m, and its share of the pixel is the coverage.
void addSample(const Color& c, Aov aov, glm::dvec3& sum, glm::dvec3& squares, int& counted, ThreadState& ts) {
  if (!isFinite(c)) {
    ++ts.counts.nonfiniteSamples;
    return;
  }
  if (geometric(aov) && c.r == kNoHit) return;
  sum += glm::dvec3(c);
  squares += glm::dvec3(c) * glm::dvec3(c);
  ++counted;
}

// The variance of a pixel's mean from its samples' spread, s^2 / n (0 below 2 samples).
Color varianceOfMean(const glm::dvec3& sum, const glm::dvec3& squares, int counted) {
  if (counted < 2) return Color(0.0f);
  const double n = counted;
  const glm::dvec3 mean = sum / n;
  return Color(glm::max((squares - n * mean * mean) / (n - 1.0) / n, glm::dvec3(0.0)));
}

// A mean above float range is clamped to it (the writer clamps further). A pixel with
// no sample counted is 0: black, or for a geometric view "no hit" (coverage 0).
void storePixel(const glm::dvec3& sum, int counted, Aov aov, int spp, size_t index, Image& image) {
  const double top = std::numeric_limits<float>::max();
  image.pixels[index] = counted > 0 ? Color(glm::min(sum / double(counted), glm::dvec3(top)))
                                    : Color(0.0f);
  if (geometric(aov)) image.coverage[index] = static_cast<float>(counted) / static_cast<float>(spp);
}

// Camera sample `s` of this pass: its random stream and its offset in the pixel. One
// pass keeps its spp jittered strata (the pixel centre at spp 1). Progressive passes
// take point pass x spp + s of the pixel's own scrambled (0,2)-sequence: each pass
// covers the pixel evenly, any number of passes adds up to strata (spp 1 x 16 passes
// as stratified as spp 16), and a pass's samples do not depend on how many follow.
struct CameraSample {
  uint64_t key;
  Vec2 offset;
};
CameraSample cameraSample(const ShadingContext& ctx, uint64_t pixel, int s) {
  const uint64_t seed = ctx.scene.render.seed;
  const uint64_t index = static_cast<uint64_t>(ctx.pass) * ctx.scene.camera.spp + static_cast<uint64_t>(s);
  const uint64_t key = hashKey(seed, pixel, index);
  if (ctx.passes > 1) {
    // The scramble's stream is a sample index no frame reaches (passes x spp < 2^32).
    return {key, sobol02(static_cast<uint32_t>(index), hashKey(seed, pixel, ~uint64_t(0)))};
  }
  Rng rng(key);
  return {key, stratified2D(s, ctx.scene.camera.spp, rng)};
}

// The packet path's per-thread buffers, sized for one tile on first use.
struct TileBuffers {
  std::vector<glm::ivec2> pixels;
  std::vector<uint64_t> keys;
  std::vector<Ray> rays;
  std::vector<Hit> hits;
  std::vector<glm::dvec3> sums, squares;
  std::vector<int> counted;
  std::vector<uint32_t> known, blocked;
  PrimaryShadowScratch shadows;
};

// One tile with its camera rays as packets: per sample index, every pixel's camera ray
// (the same jitter, from the same (seed, pixel, sample) stream) is traced in packets,
// then their shadow rays to eligible lights, then each pixel is shaded from its hit.
// Each pixel still adds its samples in sample order, so the sums equal the single path's.
void renderTilePackets(const ShadingContext& ctx, const CameraRays& camera, Aov aov,
                       uint32_t shadowLights, int x0, int y0, int x1, int y1, TileBuffers& b,
                       ThreadState& ts, Image& image, Image* variance) {
  const Camera& cam = ctx.scene.camera;
  const size_t cap = static_cast<size_t>(x1 - x0) * static_cast<size_t>(y1 - y0);
  if (b.pixels.size() < cap) {
    b.pixels.resize(cap); b.keys.resize(cap); b.rays.resize(cap); b.hits.resize(cap); b.sums.resize(cap); b.squares.resize(cap);
    b.counted.resize(cap); b.known.resize(cap); b.blocked.resize(cap);
  }
  // Pixels in 4x4 blocks: a 16-ray packet covers a square of the film, not a row.
  int n = 0;
  for (int by = y0; by < y1; by += 4)
    for (int bx = x0; bx < x1; bx += 4)
      for (int y = by; y < std::min(by + 4, y1); ++y)
        for (int x = bx; x < std::min(bx + 4, x1); ++x) b.pixels[static_cast<size_t>(n++)] = {x, y};
  for (int i = 0; i < n; ++i) { b.sums[i] = b.squares[i] = glm::dvec3(0.0); b.counted[i] = 0; }
  for (int s = 0; s < cam.spp; ++s) {
    for (int i = 0; i < n; ++i) {
      const glm::ivec2 p = b.pixels[i];
      const CameraSample cs = cameraSample(ctx, static_cast<uint64_t>(p.y) * cam.width + p.x, s);
      b.keys[i] = cs.key;
      b.rays[i] = camera.generate(p.x + cs.offset.x, p.y + cs.offset.y);
    }
    ctx.tracer.intersectPacket(b.rays.data(), n, b.hits.data());
    tracePrimaryShadows(ctx, shadowLights, b.rays.data(), b.hits.data(), n, b.known.data(),
                        b.blocked.data(), b.shadows);
    for (int i = 0; i < n; ++i) {
      beginSample(ts, b.keys[i]);
      ts.knownShadows = b.known[i];
      ts.blockedShadows = b.blocked[i];
      const Hit* hit = b.hits[i].valid() ? &b.hits[i] : nullptr;
      addSample(shadeTraced(ctx, b.rays[i], hit, aov, ts), aov, b.sums[i], b.squares[i], b.counted[i], ts);
    }
  }
  ts.knownShadows = ts.blockedShadows = 0;
  for (int i = 0; i < n; ++i) {
    const size_t index = static_cast<size_t>(b.pixels[i].y) * cam.width + b.pixels[i].x;
    storePixel(b.sums[i], b.counted[i], aov, cam.spp, index, image);
    if (variance) variance->pixels[index] = varianceOfMean(b.sums[i], b.squares[i], b.counted[i]);
  }
}

}  // namespace

Image renderImage(const ShadingContext& ctx, const RenderOptions& options, RayCounts& counts) {
  const Camera& cam = ctx.scene.camera;
  CameraRays camera(cam);
  Image image(cam.width, cam.height);
  if (options.variance) *options.variance = Image(cam.width, cam.height);
  if (geometric(options.aov)) {
    image.content = options.aov == Aov::Depth ? ImageContent::Depth : ImageContent::Normal;
    image.coverage.assign(image.pixels.size(), 0.0f);
  }
  const int tile = options.tileSize;
  const int tilesX = (cam.width + tile - 1) / tile, tilesY = (cam.height + tile - 1) / tile;
  const int numTiles = tilesX * tilesY;
  tbb::enumerable_thread_specific<ThreadState> states;
  tbb::enumerable_thread_specific<TileBuffers> buffers;
  const bool packets = ctx.choices.packets;
  const bool direct = options.aov == Aov::Beauty || options.aov == Aov::Direct;
  const uint32_t shadowLights = packets ? packetShadowLights(ctx, direct) : 0;
  progressExpect(options.tiles, static_cast<uint64_t>(numTiles));

  tbb::parallel_for(tbb::blocked_range<int>(0, numTiles, 1), [&](const tbb::blocked_range<int>& r) {
    ThreadState& ts = states.local();
    for (int t = r.begin(); t != r.end(); ++t) {
      int x0 = (t % tilesX) * tile, y0 = (t / tilesX) * tile;
      int x1 = std::min(x0 + tile, cam.width), y1 = std::min(y0 + tile, cam.height);
      if (packets) {
        renderTilePackets(ctx, camera, options.aov, shadowLights, x0, y0, x1, y1, buffers.local(), ts, image,
                            options.variance);
      } else {
        for (int y = y0; y < y1; ++y) {
          for (int x = x0; x < x1; ++x) {
            uint64_t pixel = static_cast<uint64_t>(y) * cam.width + x;
            glm::dvec3 sum(0.0), squares(0.0);  // double: many finite samples near float's top cannot overflow
            int counted = 0;
            for (int s = 0; s < cam.spp; ++s) {
              const CameraSample cs = cameraSample(ctx, pixel, s);
              beginSample(ts, cs.key);
              Color c = shadeSample(ctx, camera.generate(x + cs.offset.x, y + cs.offset.y), options.aov, ts);
              addSample(c, options.aov, sum, squares, counted, ts);
            }
            storePixel(sum, counted, options.aov, cam.spp, static_cast<size_t>(pixel), image);
            if (options.variance) options.variance->pixels[pixel] = varianceOfMean(sum, squares, counted);
          }
        }
      }
      progressAdd(options.tiles, 1);
    }
  });

  for (const ThreadState& ts : states) counts += ts.counts;
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
  const CameraSample cs = cameraSample(ctx, static_cast<uint64_t>(y) * cam.width + x, 0);
  beginSample(ts, cs.key);
  CameraRays camera(cam);
  Ray ray = camera.generate(x + cs.offset.x, y + cs.offset.y);
  ctx.choices.integrator->tree(ctx, ray, ts);
  return tree;
}

}  // namespace penumbra
