// Shadow segments through media (trace/medium_shadow.h).
#include "trace/medium_shadow.h"
#include "core/light_sample.h"
#include "core/media/density_grid.h"
#include "core/media/homogeneous.h"
#include "core/media/tracking.h"
#include "trace/medium_walk.h"

namespace penumbra {
namespace {

enum : uint64_t { kTransmittanceStream = 0x7472616e736d6974ull };  // "transmit": grids' tracking draws

}  // namespace

bool gridSpan(const Medium& m, const Ray& ray, float& a, float& b) {
  if (m.homogeneous()) return true;
  // The slab test; a zero direction component gives +-infinity, which min/max order.
  const Vec3 inv = 1.0f / ray.dir;
  const Vec3 t0 = (m.density->worldLo - ray.origin) * inv, t1 = (m.density->worldHi - ray.origin) * inv;
  const Vec3 lo = glm::min(t0, t1), hi = glm::max(t0, t1);
  a = std::max(a, maxComponent(lo));
  b = std::min(b, std::min(hi.x, std::min(hi.y, hi.z)));
  return b > a;
}

Color stretchTransmittance(const Medium& m, const Ray& ray, float a, float b, ThreadState& ts) {
  if (m.homogeneous()) return transmittance(m.sigmaT(), b - a);  // an infinite stretch too
  if (!gridSpan(m, ray, a, b)) return Color(1.0f);
  Rng rng(hashKey(ts.sampleKey ^ kTransmittanceStream, ts.mediumDraws++));
  return mediumTransmittance(m, ray.origin, ray.dir, a, b, rng);
}

Color segmentTransmittance(const ShadingContext& ctx, const Ray& ray, float tEnd, int medium, ThreadState& ts) {
  const std::vector<Medium>& media = ctx.scene.media;
  Color t(1.0f);
  bool counted = false;
  walkStretches(ctx.tracer, ray, tEnd, medium, [&](int mi, float from, float to) {
    if (mi == kNoMedium) return true;
    if (!counted) ++ts.counts.transmittanceRays;
    counted = true;
    t *= stretchTransmittance(media[static_cast<size_t>(mi)], ray, from, to, ts);
    return maxComponent(t) > 0.0f;
  });
  return t;
}

Color lightTransmittance(const ShadingContext& ctx, const Ray& ray, float margin, uint32_t li, int medium,
                         ThreadState& ts) {
  float tEnd = ray.tMax + margin;
  if (lightTraits(ctx.scene.lights[li]).shadowTest == ShadowTest::FirstHitIsEmitter) {
    // Near a sphere light's silhouette the ray from the lifted origin can enter the
    // sphere before the sampled point: whatever it meets first decides, and meeting
    // the light itself means it arrived.
    Hit hit;
    if (ctx.tracer.intersect(ray, hit)) {
      if (ctx.scene.materials[ctx.tracer.materialOf(hit)].light != static_cast<int>(li)) return Color(0.0f);
      tEnd = hit.t;
    }
  } else if (ctx.tracer.occluded(ray)) {
    return Color(0.0f);
  }
  if (!ctx.scene.hasMedia()) return Color(1.0f);
  return segmentTransmittance(ctx, ray, tEnd, medium, ts);
}

}  // namespace penumbra
