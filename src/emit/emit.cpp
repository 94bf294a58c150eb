// Shadow and indirect photon emission. Each batch draws from its own random
// stream keyed by (seed, map, light, batch index within the light); the maps read the batches in
// batch order, so the stored arrays do not depend on the thread count.
#include "emit/emit.h"
#include "core/bsdf.h"
#include "core/color.h"
#include "core/light_sample.h"
#include "core/optics.h"
#include "core/rng.h"
#include "core/sampling.h"
#include "emit/batch_buffers.h"
#include "emit/budget.h"
#include "emit/light_reach.h"
#include "emit/photon_pass.h"
#include <tbb/parallel_for.h>

namespace penumbra {
namespace {

// Follows one line from the light through every surface: the first hit is
// direct, all later ones are in shadow, opaque once anything opaque was crossed.
void traceShadowLine(const TraceScene& tracer, const Vec3& origin, const Vec3& dir, uint16_t light,
                     uint8_t stratum, int maxHits, BatchAppender<ShadowPhoton>& out) {
  const std::vector<Material>& materials = tracer.scene().materials;
  Ray ray{origin, dir};
  ShadowKind kind = kDirect;
  for (int h = 0; h < maxHits; ++h) {
    Hit hit;
    if (!tracer.intersect(ray, hit)) return;
    SurfaceRecord s = tracer.surface(ray, hit, kSurfaceGeometric);
    out.push_back({s.position, encodeOctahedral(s.ng), light, kind, stratum, !s.frontFace});
    if (kind != kShadowOpaque) kind = materials[s.material].transparent ? kShadowGlass : kShadowOpaque;
    ray.origin = spawnOrigin(s, dir);
  }
}

// One indirect photon path: stored at every hit (classic) or every hit after
// the first (density, whose direct part comes from the Phong term instead).
void traceIndirectPath(const Scene& scene, const TraceScene& tracer, Ray ray, Color power, Rng& rng,
                       bool storeFirstHit, BatchAppender<IndirectPhoton>& out) {
  const PhotonSettings& ps = scene.photons;
  for (int bounce = 0; bounce <= ps.maxBounces; ++bounce) {
    Hit hit;
    if (!tracer.intersect(ray, hit)) return;
    SurfaceRecord s = tracer.surface(ray, hit, kSurfaceShadingNormal);
    const Material& m = scene.materials[s.material];
    if (bounce > 0 || storeFirstHit) {
      out.push_back({s.position, power, encodeOctahedral(ray.dir), encodeOctahedral(s.ng)});
    }
    // The report's roulette, behind the classic BSDF: p_r reflects, p_t transmits,
    // the rest is absorbed; a survivor's power never grows in any channel.
    float xi = rng.uniform();
    float u1 = rng.uniform(), u2 = rng.uniform();
    const Bsdf bsdf = makeBsdf(m, BsdfFamily::Phong, ps.sampling, Color(tracer.vertexColor(hit)));
    BsdfSample bs = sampleBsdf(bsdf, {s.ns, s.ng, s.frontFace}, -ray.dir, xi, u1, u2);
    if (!bs.valid) return;  // absorbed
    Vec3 dir = bs.wi;
    power *= bs.weight;
    // Written so a NaN or Inf power (an overflowed weight) ends the path, never gets stored.
    if (!(maxComponent(power) > 0.0f) || !isFinite(power)) return;
    ray = Ray{spawnOrigin(s, dir), dir};
  }
}

std::vector<double> classicWeights(const Scene& scene) {
  std::vector<double> power(scene.lights.size(), 0.0);
  for (size_t l = 0; l < scene.lights.size(); ++l) power[l] = classicPhotonWeight(scene.lights[l]);
  return power;
}
}  // namespace

PhotonTally& PhotonTally::operator+=(const PhotonTally& o) {
  emitted += o.emitted; escaped += o.escaped; absorbed += o.absorbed; capped += o.capped;
  for (MapKind k : kAllMaps) stored[k] += o.stored[k];
  return *this;
}

std::vector<uint64_t> splitBudget(const Scene& scene, uint64_t total, const std::vector<float>& reach) {
  return splitByWeight(reachWeighted(classicWeights(scene), reach), total);
}

void emitPhotons(const Scene& scene, const TraceScene& tracer, const EmitOptions& options, EmittedPhotons& maps) {
  const std::vector<double> weights = classicWeights(scene);
  const PhotonSettings& ps = scene.photons;
  const SceneSphere bounds = tracer.boundingSphere();
  const uint64_t seed = scene.render.seed;
  enum : uint64_t { kShadowStream = 1, kIndirectStream = 2 };

  const MapCounts& budgets = options.budgets;
  const std::vector<uint64_t> shadowCounts =
      splitBudget(scene, options.maps[MapKind::Shadow] ? budgets[MapKind::Shadow] : 0);
  maps.batches.get<MapKind::Shadow>() = runPhotonPass<ShadowPhoton>(
      weights, shadowCounts, options, &maps.cuts[MapKind::Shadow], maps.emitted[MapKind::Shadow],
      [&](const PhotonBatch& batch) {
        const Light& light = scene.lights[batch.light];
        Rng rng(hashKey(seed, kShadowStream, batchStreamKey(batch)));
        const Kronecker4 starts(rng);
        return [&light, &bounds, &tracer, &options, index = static_cast<uint16_t>(batch.light), rng, starts,
                i = uint64_t(0)](BatchAppender<ShadowPhoton>& out) mutable {
          const PhotonRay r = shadowPhotonStart(light, bounds, starts, i++, rng);
          traceShadowLine(tracer, r.origin, r.dir, index, r.stratum, options.maxHitsPerLine, out);
        };
      });

  const std::vector<double> indirectWeights = reachWeighted(weights, options.reach[MapKind::Indirect]);
  const std::vector<uint64_t> indirectCounts =
      splitByWeight(indirectWeights, options.maps[MapKind::Indirect] ? budgets[MapKind::Indirect] : 0);
  const bool storeFirstHit = ps.estimator == IndirectEstimator::Classic;
  maps.batches.get<MapKind::Indirect>() = runPhotonPass<IndirectPhoton>(
      indirectWeights, indirectCounts, options, &maps.cuts[MapKind::Indirect], maps.emitted[MapKind::Indirect],
      [&](const PhotonBatch& batch) {
        const Light& light = scene.lights[batch.light];
        // Each photon carries an equal share of the light's flux (4 pi I for a point light).
        const Color power = classicPhotonPower(light, bounds, static_cast<float>(indirectCounts[batch.light]));
        return [&scene, &tracer, &light, &bounds, power, storeFirstHit,
                rng = Rng(hashKey(seed, kIndirectStream, batchStreamKey(batch)))](
                   BatchAppender<IndirectPhoton>& out) mutable {
          const PhotonRay r = classicPhotonStart(light, bounds, rng);
          traceIndirectPath(scene, tracer, Ray{r.origin, r.dir}, power * r.weight, rng, storeFirstHit, out);
        };
      });

  double intensity = 0.0;
  for (const Light& l : scene.lights) intensity += classicPhotonWeight(l);
  if (maps.emitted[MapKind::Indirect] > 0 && intensity > 0.0) {
    maps.classicScale = static_cast<float>(maps.emitted[MapKind::Indirect] / (4.0 * kPi * intensity));
  }
}

}  // namespace penumbra
