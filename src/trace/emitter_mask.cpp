// The emitter mask: camera rays that add up only the emitters' glow (the physical
// tracer's kTermEmitters), on a grid per pixel, then grown by one pixel.
#include "trace/emitter_mask.h"
#include "core/rng.h"
#include "trace/camera.h"
#include "trace/physical.h"
#include <tbb/enumerable_thread_specific.h>
#include <tbb/parallel_for.h>
#include <algorithm>

namespace penumbra {
namespace {

// The mask's stream of sample keys (a thin lens's), apart from the render's and the probes'.
constexpr uint64_t kMaskStream = uint64_t(1) << 41;

bool seesEmitter(const ShadingContext& ctx, const CameraRays& camera, int x, int y, uint64_t pixel, ThreadState& ts) {
  for (int j = 0; j < kEmitterGrid * kEmitterGrid; ++j) {
    const uint64_t key = hashKey(ctx.scene.render.seed, pixel, kMaskStream + uint64_t(j));
    const float ox = (float(j % kEmitterGrid) + 0.5f) / kEmitterGrid, oy = (float(j / kEmitterGrid) + 0.5f) / kEmitterGrid;
    beginSample(ts, key);
    const Color glow = tracePhysical(ctx, camera.generate(x + ox, y + oy, key), 0, Color(1.0f), RayKind::Camera,
                                     kTermEmitters, -1, ts, ctx.scene.cameraMedium);
    if (maxComponent(glow) > 0.0f) return true;
  }
  return false;
}

}  // namespace

EmitterMask emitterMask(const ShadingContext& ctx, const PixelBounds* bounds) {
  if (ctx.scene.render.model != ShadingModel::Physical) return {};
  const int w = ctx.scene.camera.width, h = ctx.scene.camera.height;
  const PixelBounds area = bounds ? *bounds : PixelBounds::frame(w, h);
  // The grid is traced one pixel beyond the bounds, so a tile grows its mask as the
  // whole frame does.
  const PixelBounds grown{std::max(0, area.x0 - 1), std::min(w, area.x1 + 1), std::max(0, area.y0 - 1),
                          std::min(h, area.y1 + 1)};
  std::vector<uint8_t> hit(size_t(w) * h, 0);
  tbb::enumerable_thread_specific<ThreadState> states;
  const CameraRays camera(ctx.scene.camera);
  tbb::parallel_for(grown.y0, grown.y1, [&](int y) {
    ThreadState& ts = states.local();
    for (int x = grown.x0; x < grown.x1; ++x) {
      const size_t i = size_t(y) * w + x;
      hit[i] = seesEmitter(ctx, camera, x, y, i, ts) ? 1 : 0;
    }
  });
  EmitterMask mask(hit.size(), 0);
  for (int y = area.y0; y < area.y1; ++y)
    for (int x = area.x0; x < area.x1; ++x) {
      uint8_t any = 0;
      for (int dy = -1; dy <= 1; ++dy)
        for (int dx = -1; dx <= 1; ++dx) {
          const int xx = x + dx, yy = y + dy;
          if (xx >= 0 && xx < w && yy >= 0 && yy < h) any |= hit[size_t(yy) * w + xx];
        }
      mask[size_t(y) * w + x] = any;
    }
  return mask;
}

}  // namespace penumbra
