// The media along a camera or specular ray (trace/medium_path.h).
#include "trace/medium_path.h"
#include "core/media/density_grid.h"
#include "core/media/tracking.h"
#include "gather/volume_estimate.h"
#include "trace/medium_shadow.h"
#include "trace/medium_walk.h"
#include "trace/physical.h"
#include "trace/volume_direct.h"

namespace penumbra {
namespace {

enum : uint64_t { kStretchStream = 0x73747265746368ull };  // "stretch": a stretch's distance and light samples

// integral over [a, b] of T(a, t) sigma_a Le dt: closed form when homogeneous, else one
// distance sample (the emission is where the density is, as the extinction is).
Color emissionAlong(const Medium& m, const Ray& ray, float a, float b, Rng& rng, ThreadState& ts) {
  if (!(maxComponent(m.emission) > 0.0f) || !(maxComponent(m.sigmaA) > 0.0f)) return Color(0.0f);
  const Color st = m.sigmaT();
  if (m.homogeneous()) {
    Color sum(0.0f);
    const Color source = m.sigmaA * m.emission;  // sigma_a > 0 where the source is, so sigma_t > 0
    for (int c = 0; c < 3; ++c) {
      if (source[c] > 0.0f) sum[c] = source[c] * -std::expm1(-st[c] * (b - a)) / st[c];  // 1 - 0 over an infinite one
    }
    return sum;
  }
  if (!gridSpan(m, ray, a, b)) return Color(0.0f);
  const FreeFlight flight(m, a, b);
  const DistanceSample d = flight.sample(rng.uniform());
  if (!(d.pdf > 0.0f)) return Color(0.0f);
  ++ts.counts.mediumSamples;
  return emissionAt(m, ray.origin + d.t * ray.dir) * stretchTransmittance(m, ray, a, d.t, ts) / d.pdf;
}

}  // namespace

MediumStretch traceMediumStretch(const ShadingContext& ctx, const Ray& ray, float tEnd, int medium, uint8_t terms,
                                 ThreadState& ts) {
  MediumStretch out;
  const VolumePhotonMap* volumeMap = ctx.maps.get<MapKind::Volume>();
  out.medium = walkStretches(ctx.tracer, ray, tEnd, medium, [&](int mi, float a, float b) {
    if (mi == kNoMedium) return true;
    ++ts.counts.mediumSegments;
    const Medium& m = ctx.scene.media[static_cast<size_t>(mi)];
    Rng rng(hashKey(ts.sampleKey ^ kStretchStream, ts.mediumDraws++));
    Color added(0.0f);
    if (terms & kTermDirect) added += volumeDirect(ctx, ray, a, b, mi, rng, ts);
    if (terms & (kTermDirect | kTermEmitters)) added += emissionAlong(m, ray, a, b, rng, ts);
    if ((terms & kTermGlobal) && volumeMap && !volumeMap->empty() && maxComponent(m.sigmaS) > 0.0f) {
      ++ts.counts.volumeGathers;
      const PhotonGather gather = ctx.gathers[MapKind::Volume];
      const VolumeEstimate e =
          volumeRadiance(*volumeMap, VolumeQuery{ray.origin, ray.dir, a, b, mi}, m, gather.k, gather.maxRadius, *ts.scratch);
      ts.counts.volumeNeighbours += e.found;
      added += e.value;
    }
    out.radiance += out.transmittance * added;
    out.transmittance *= stretchTransmittance(m, ray, a, b, ts);
    return maxComponent(out.transmittance) > 0.0f;
  });
  return out;
}

}  // namespace penumbra
