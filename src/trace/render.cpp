// Tiles are scheduled by tbb::parallel_for and write disjoint pixels; every
// sample's random numbers come from (seed, pixel, sample), never from a thread.
#include "trace/render.h"
#include "core/adaptive_sampling.h"
#include "core/error.h"
#include "core/rng.h"
#include "trace/camera.h"
#include "trace/light_visibility.h"
#include <tbb/blocked_range.h>
#include <tbb/enumerable_thread_specific.h>
#include <tbb/parallel_for.h>
#include <atomic>
#include <cmath>
#include <limits>
#include <numeric>

namespace penumbra {

namespace {

// Depth and normals carry no light (core/view.h's rule).
bool geometric(Aov aov) { return !readsLight(aov); }

// Geometric views always keep their coverage; views of light keep it when the
// background is transparent (then their files carry A = coverage).
bool keepsCoverage(const ShadingContext& ctx, Aov aov) {
  return geometric(aov) || ctx.scene.render.transparentBackground;
}

// A geometric view's sample that hit nothing: no depth is -2 and no normal has r = -2,
// so the pixel's mean can leave it out and count it against the coverage instead.
constexpr float kNoHit = -2.0f;

// One sample of the chosen view: the transport model's integrator for views that
// read light; here the physical values for depth (distance along the camera ray) and
// normal (world-space shading normal, facing the ray), which writers map for display
// (io/aov_display.h). `hit`: the ray's first hit, already traced (alone or in a
// packet); null on a miss. A transparent background makes a miss 0 after the
// integrator ran, so the ray counts stay those of the opaque render.
Color shadeTraced(const ShadingContext& ctx, const Ray& ray, const Hit* hit, Aov aov, ThreadState& ts) {
  ts.raysLeft = kMaxRaysPerSample;
  if (!geometric(aov)) {
    const Color c = ctx.choices.integrator->sample(ctx, ray, hit, aov, ts);
    return hit || !ctx.scene.render.transparentBackground ? c : Color(0.0f);
  }
  ++ts.counts.camera;
  if (!hit) return Color(kNoHit);
  if (aov == Aov::Depth) return Color(hit->t);
  return ctx.tracer.surface(ray, *hit, kSurfaceShadingNormal).ns;
}


// A pixel's running sums: all its samples, and those of sequence B (odd samples of
// one pass), in double: many finite samples near float's top cannot overflow; and
// how many of the samples counted hit geometry.
struct PixelSums {
  glm::dvec3 sum{0.0}, oddSum{0.0}, smoothing{0.0};
  int counted = 0, oddCounted = 0, hits = 0, smoothingCounted = 0;

  // One sample in. A NaN or Inf sample would poison the pixel (or be written as 0 and
  // hide): drop it, count it, and let the pixel's other samples stand. Geometric views
  // average only the samples that hit: a miss is "no depth", not 0 m, and its share
  // of the pixel is the coverage.
  void add(const Color& c, Aov aov, bool odd, bool hit, ThreadState& ts) {
    if (!isFinite(c)) {
      ++ts.counts.nonfiniteSamples;
      return;
    }
    if (geometric(aov) && c.r == kNoHit) return;
    sum += glm::dvec3(c);
    if (isFinite(ts.smoothing)) smoothing += glm::dvec3(ts.smoothing), ++smoothingCounted;
    ++counted;
    hits += hit ? 1 : 0;
    if (odd) {
      oddSum += glm::dvec3(c);
      ++oddCounted;
    }
  }

  // The standard error of the pixel's mean from its even and odd samples' means (two
  // independent estimates): the root of n_e n_o / n^2 times their difference squared,
  // in double. At most the larger mean: finite (clamped as the pixel is).
  Color standardError() const {
    const int evenCounted = counted - oddCounted;
    if (evenCounted < 1 || oddCounted < 1) return Color(0.0f);
    const glm::dvec3 d = (sum - oddSum) / double(evenCounted) - oddSum / double(oddCounted);
    const double share = std::sqrt(double(evenCounted) * oddCounted) / double(counted);
    return Color(glm::min(share * glm::abs(d), glm::dvec3(std::numeric_limits<float>::max())));
  }
};

// A mean above float range is clamped to it (the writer clamps further). A pixel with
// no sample counted is 0: black, or for a geometric view "no hit" (coverage 0). A view
// of light's coverage is over the same samples as its colour, so the colour is
// premultiplied by it exactly (a miss adds 0 to the colour and nothing to the hits).
void storePixel(const PixelSums& p, Aov aov, int spp, size_t index, Image& image, Image* standardError,
                Image* smoothing) {
  const double top = std::numeric_limits<float>::max();
  image.pixels[index] = p.counted > 0 ? Color(glm::min(p.sum / double(p.counted), glm::dvec3(top))) : Color(0.0f);
  if (geometric(aov)) image.coverage[index] = static_cast<float>(p.counted) / static_cast<float>(spp);
  else if (!image.coverage.empty() && p.counted > 0)
    image.coverage[index] = static_cast<float>(double(p.hits) / double(p.counted));
  if (standardError) standardError->pixels[index] = p.standardError();
  if (smoothing && p.smoothingCounted > 0)
    smoothing->pixels[index] = Color(glm::clamp(p.smoothing / double(p.smoothingCounted), -top, top));
}

// Camera sample `s` of this pass: its random stream and its offset in the pixel. One
// sample of one pass is the pixel centre. Otherwise samples come from two scrambled
// (0,2)-sequences of the pixel's own, A and B, independent of each other: passes
// alternate between them (pass p takes its spp points from p's sequence, after those
// of earlier passes), and one pass alternates its samples. So spp 1 x 16 passes takes
// the points spp 16 x 1 pass takes; each sequence's points add up to strata; a pass's
// samples do not depend on how many follow; and the means of A and B are two
// independent estimates of the pixel, whose difference is the error estimate's.
struct CameraSample {
  uint64_t key;
  Vec2 offset;
};
CameraSample cameraSample(const ShadingContext& ctx, uint64_t pixel, int s) {
  const uint64_t seed = ctx.scene.render.seed;
  const uint32_t spp = static_cast<uint32_t>(ctx.scene.camera.spp);
  const uint64_t index = static_cast<uint64_t>(ctx.pass) * spp + static_cast<uint64_t>(s);
  const uint64_t key = hashKey(seed, pixel, index);
  if (ctx.passes <= 1 && spp == 1) return {key, {0.5f, 0.5f}};
  const bool passes = ctx.passes > 1;
  const uint32_t sequence = passes ? ctx.pass % 2 : static_cast<uint32_t>(s) % 2;
  const uint32_t point = passes ? ctx.pass / 2 * spp + static_cast<uint32_t>(s) : static_cast<uint32_t>(s) / 2;
  // The scrambles' streams are sample indices no frame reaches (passes x spp < 2^32).
  return {key, sobol02(point, hashKey(seed, pixel, ~uint64_t(sequence)))};
}

// Extra sample `e` of this pass (adaptive sampling): its stream is past every base
// sample's (passes x spp < 2^32), a run of kAdaptiveSppLimit per pass; its offset is
// point e of a (0,2)-sequence of the pass's own, scrambled apart from A's and B's.
CameraSample extraSample(const ShadingContext& ctx, uint64_t pixel, int e) {
  const uint64_t seed = ctx.scene.render.seed;
  const uint64_t index = (uint64_t(1) << 32) + uint64_t(ctx.pass) * kAdaptiveSppLimit + uint64_t(e);
  return {hashKey(seed, pixel, index), sobol02(static_cast<uint32_t>(e), hashKey(seed, pixel, ~uint64_t(2 + ctx.pass)))};
}

// One camera sample traced alone and added to the pixel's sums.
inline void addSample(const ShadingContext& ctx, const CameraRays& camera, Aov aov, int x, int y,
                      const CameraSample& cs, bool odd, PixelSums& sums, ThreadState& ts) {
  beginSample(ts, cs.key);
  const Ray ray = camera.generate(x + cs.offset.x, y + cs.offset.y, cs.key);
  Hit hit;
  const bool found = ctx.tracer.intersect(ray, hit);
  sums.add(shadeTraced(ctx, ray, found ? &hit : nullptr, aov, ts), aov, odd, found, ts);
}

// The pixel's extra samples of this pass, after its spp (their parity goes on
// alternating, so one pass's even and odd samples stay two equal sets).
void addExtraSamples(const ShadingContext& ctx, const CameraRays& camera, Aov aov, int x, int y, int count,
                     PixelSums& sums, ThreadState& ts) {
  const Camera& cam = ctx.scene.camera;
  const uint64_t pixel = static_cast<uint64_t>(y) * cam.width + x;
  for (int e = 0; e < count; ++e) {
    addSample(ctx, camera, aov, x, y, extraSample(ctx, pixel, e), (cam.spp + e) % 2 == 1, sums, ts);
  }
}

// The packet path's per-thread buffers, sized for one tile on first use.
struct TileBuffers {
  std::vector<glm::ivec2> pixels;
  std::vector<uint64_t> keys;
  std::vector<Ray> rays;
  std::vector<Hit> hits;
  std::vector<PixelSums> sums;
  std::vector<uint32_t> known, blocked;
  PrimaryShadowScratch shadows;
};

// One tile with its camera rays as packets: per sample index, every pixel's camera ray
// (the same jitter, from the same (seed, pixel, sample) stream) is traced in packets,
// then their shadow rays to eligible lights, then each pixel is shaded from its hit.
// Each pixel still adds its samples in sample order, so the sums equal the single path's.
void renderTilePackets(const ShadingContext& ctx, const CameraRays& camera, Aov aov,
                       uint32_t shadowLights, int x0, int y0, int x1, int y1, const PixelBounds& keep,
                       const std::vector<uint16_t>* extra, TileBuffers& b, ThreadState& ts, Image& image,
                       Image* standardError, Image* smoothing) {
  const Camera& cam = ctx.scene.camera;
  const size_t cap = static_cast<size_t>(x1 - x0) * static_cast<size_t>(y1 - y0);
  if (b.pixels.size() < cap) {
    b.pixels.resize(cap); b.keys.resize(cap); b.rays.resize(cap); b.hits.resize(cap); b.sums.resize(cap);
    b.known.resize(cap); b.blocked.resize(cap);
  }
  // Pixels in 4x4 blocks: a 16-ray packet covers a square of the film, not a row.
  int n = 0;
  for (int by = y0; by < y1; by += 4)
    for (int bx = x0; bx < x1; bx += 4)
      for (int y = by; y < std::min(by + 4, y1); ++y)
        for (int x = bx; x < std::min(bx + 4, x1); ++x) b.pixels[static_cast<size_t>(n++)] = {x, y};
  // A part of the frame still traces the whole tile's packets (a packet's traversal
  // order decides ties between faces, so its rays must be the whole frame's), but
  // shades and stores only the pixels inside `keep`.
  const bool whole = keep.x0 <= x0 && keep.y0 <= y0 && keep.x1 >= x1 && keep.y1 >= y1;
  for (int i = 0; i < n; ++i) b.sums[i] = PixelSums();
  for (int s = 0; s < cam.spp; ++s) {
    for (int i = 0; i < n; ++i) {
      const glm::ivec2 p = b.pixels[i];
      const CameraSample cs = cameraSample(ctx, static_cast<uint64_t>(p.y) * cam.width + p.x, s);
      b.keys[i] = cs.key;
      b.rays[i] = camera.generate(p.x + cs.offset.x, p.y + cs.offset.y, cs.key);
    }
    ctx.tracer.intersectPacket(b.rays.data(), n, b.hits.data());
    tracePrimaryShadows(ctx, shadowLights, b.rays.data(), b.hits.data(), n, b.known.data(),
                        b.blocked.data(), b.shadows);
    for (int i = 0; i < n; ++i) {
      if (!whole && !keep.contains(b.pixels[i].x, b.pixels[i].y)) continue;
      beginSample(ts, b.keys[i]);
      ts.knownShadows = b.known[i];
      ts.blockedShadows = b.blocked[i];
      const Hit* hit = b.hits[i].valid() ? &b.hits[i] : nullptr;
      b.sums[i].add(shadeTraced(ctx, b.rays[i], hit, aov, ts), aov, s % 2 == 1, hit != nullptr, ts);
    }
  }
  ts.knownShadows = ts.blockedShadows = 0;
  for (int i = 0; i < n; ++i) {
    if (!whole && !keep.contains(b.pixels[i].x, b.pixels[i].y)) continue;
    const size_t index = static_cast<size_t>(b.pixels[i].y) * cam.width + b.pixels[i].x;
    if (extra && (*extra)[index] > 0) addExtraSamples(ctx, camera, aov, b.pixels[i].x, b.pixels[i].y, (*extra)[index], b.sums[i], ts);
    storePixel(b.sums[i], aov, cam.spp, index, image, standardError, smoothing);
  }
}

}  // namespace

Color shadeCameraRay(const ShadingContext& ctx, const Ray& ray, Aov aov, ThreadState& ts) {
  Hit hit;
  const bool found = ctx.tracer.intersect(ray, hit);
  return shadeTraced(ctx, ray, found ? &hit : nullptr, aov, ts);
}

Image renderImage(const ShadingContext& ctx, const RenderOptions& options, RayCounts& counts) {
  const Camera& cam = ctx.scene.camera;
  CameraRays camera(cam);
  Image image(cam.width, cam.height);
  if (options.standardError) *options.standardError = Image(cam.width, cam.height);
  if (options.smoothing) *options.smoothing = Image(cam.width, cam.height);
  if (geometric(options.aov)) image.content = options.aov == Aov::Depth ? ImageContent::Depth : ImageContent::Normal;
  if (keepsCoverage(ctx, options.aov)) image.coverage.assign(image.pixels.size(), 0.0f);
  const int tile = options.tileSize;
  const int tilesX = (cam.width + tile - 1) / tile, tilesY = (cam.height + tile - 1) / tile;
  const int numTiles = tilesX * tilesY;
  // A part of the frame renders the tiles that meet it, each on the whole frame's grid.
  const PixelBounds keep = options.bounds ? *options.bounds : PixelBounds::frame(cam.width, cam.height);
  std::vector<int> tiles;
  for (int t = 0; t < numTiles; ++t) {
    const int x0 = (t % tilesX) * tile, y0 = (t / tilesX) * tile;
    if (x0 < keep.x1 && x0 + tile > keep.x0 && y0 < keep.y1 && y0 + tile > keep.y0) tiles.push_back(t);
  }
  tbb::enumerable_thread_specific<ThreadState> states;
  tbb::enumerable_thread_specific<TileBuffers> buffers;
  const bool packets = ctx.choices.packets;
  const bool direct = options.aov == Aov::Beauty || options.aov == Aov::Direct;
  const uint32_t shadowLights = packets ? packetShadowLights(ctx, direct) : 0;
  progressExpect(options.tiles, static_cast<uint64_t>(tiles.size()));

  tbb::parallel_for(tbb::blocked_range<size_t>(0, tiles.size(), 1), [&](const tbb::blocked_range<size_t>& r) {
    ThreadState& ts = states.local();
    for (size_t k = r.begin(); k != r.end(); ++k) {
      const int t = tiles[k];
      int x0 = (t % tilesX) * tile, y0 = (t / tilesX) * tile;
      int x1 = std::min(x0 + tile, cam.width), y1 = std::min(y0 + tile, cam.height);
      if (packets) {
        renderTilePackets(ctx, camera, options.aov, shadowLights, x0, y0, x1, y1, keep, options.extra,
                          buffers.local(), ts, image, options.standardError, options.smoothing);
      } else {
        for (int y = y0; y < y1; ++y) {
          for (int x = x0; x < x1; ++x) {
            if (!keep.contains(x, y)) continue;
            uint64_t pixel = static_cast<uint64_t>(y) * cam.width + x;
            PixelSums sums;
            for (int s = 0; s < cam.spp; ++s) {
              addSample(ctx, camera, options.aov, x, y, cameraSample(ctx, pixel, s), s % 2 == 1, sums, ts);
            }
            if (options.extra && (*options.extra)[pixel] > 0) {
              addExtraSamples(ctx, camera, options.aov, x, y, (*options.extra)[pixel], sums, ts);
            }
            storePixel(sums, options.aov, cam.spp, static_cast<size_t>(pixel), image, options.standardError,
                       options.smoothing);
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
  Ray ray = camera.generate(x + cs.offset.x, y + cs.offset.y, cs.key);
  ctx.choices.integrator->tree(ctx, ray, ts);
  return tree;
}

}  // namespace penumbra
