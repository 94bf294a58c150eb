// Physical photon emission. The global pass shoots photons from every light in
// proportion to its power; the caustic pass aims them at the specular objects'
// bounding spheres (Jensen's projection maps) and keeps only L S+ D paths.
#include "emit/emit_physical.h"
#include "emit/photon_pass.h"
#include "core/bsdf.h"
#include "core/light_sample.h"
#include "core/rng.h"
#include "core/sampling.h"
#include "emit/batch_buffers.h"
#include "emit/budget.h"
#include "emit/caustic_aim.h"
#include <tbb/parallel_for.h>
#include <tbb/enumerable_thread_specific.h>

namespace penumbra {

namespace {

enum : uint64_t { kGlobalStream = 3, kCausticStream = 4 };

// Follows one photon; stores it at smooth surfaces as the pass dictates and plays
// Russian roulette by the sampled weight: survive with q = min(1, max weight), then
// power *= weight / q, so E[power after] = power x albedo, per channel.
void tracePhoton(const Scene& scene, const TraceScene& tracer, MapKind pass, Ray ray, Color power,
                 Rng& rng, BatchAppender<IndirectPhoton>& out, PhotonTally& tally) {
  const PhotonSettings& ps = scene.photons;
  int diffuseBounces = 0, specularBounces = 0;
  for (int bounce = 0;; ++bounce) {
    Hit hit;
    if (!tracer.intersect(ray, hit)) {
      tally.escaped += glm::dvec3(power);
      return;
    }
    if (bounce > ps.maxBounces) {
      tally.capped += glm::dvec3(power);
      return;
    }
    SurfaceRecord s = tracer.surface(ray, hit, kSurfaceShadingNormal);
    // The albedo camera paths see at this hit: the vertex colour tints the base.
    Bsdf bsdf =
        makeBsdf(scene.materials[s.material], BsdfFamily::Radiometric, ps.sampling, Color(tracer.vertexColor(hit)));
    if (hasGatheredLobe(bsdf)) {  // where a camera path reads the maps
      bool store = pass == MapKind::Global ? diffuseBounces > 0 : specularBounces > 0;
      if (store) {
        out.push_back({s.position, power, encodeOctahedral(ray.dir), encodeOctahedral(s.ng)});
        tally.stored[pass] += glm::dvec3(power);
      }
    }
    float uLobe = rng.uniform(), u1 = rng.uniform(), u2 = rng.uniform(), uRr = rng.uniform();
    BsdfSample bs = sampleBsdf(bsdf, {s.ns, s.ng, s.frontFace}, -ray.dir, uLobe, u1, u2);
    // A narrow glossy bounce is specular here, as camera paths trace it like a mirror.
    bool delta = bs.flags & (kBsdfSpecular | kBsdfNarrow);
    // The caustic pass ends at the first non-specular bounce: what follows is the
    // global map's (and a direct hit, the shadow rays').
    if (!bs.valid || (pass == MapKind::Caustic && !delta)) {
      tally.absorbed += glm::dvec3(power);
      return;
    }
    float q = std::min(1.0f, maxComponent(bs.weight));
    Color next = uRr < q ? power * bs.weight / q : Color(0.0f);
    tally.absorbed += glm::dvec3(power) - glm::dvec3(next);
    if (!(maxComponent(next) > 0.0f) || !isFinite(next)) return;  // NaN or Inf: never stored
    power = next;
    if (delta) ++specularBounces; else ++diffuseBounces;
    ray = Ray{spawnOrigin(s, bs.wi), bs.wi};
  }
}

// Each light's share of a pass's budget: its power; aimed (caustic) only the power that
// heads for the targets; unaimed times the reach, the share whose first hit can lead to
// a store.
std::vector<double> photonWeights(const Scene& scene, const SceneSphere& bounds, const std::vector<CausticAim>& aims,
                                  bool caustic, const std::vector<float>& reach) {
  std::vector<double> weights;
  for (size_t l = 0; l < scene.lights.size(); ++l) {
    const Light& light = scene.lights[l];
    double w = luminance(lightPower(light, bounds));
    if (caustic && aimsCausticPhotons(light)) {
      w *= aims[l].share;
    } else if (reach.size() == scene.lights.size()) {
      w *= reach[l];
    }
    weights.push_back(w);
  }
  return weights;
}

// Every light's caustic aim at `targets` (none for the global pass).
std::vector<CausticAim> aimsOf(const Scene& scene, const SceneSphere& bounds, const std::vector<SceneSphere>& targets) {
  enum : uint64_t { kAimStream = 5 };
  std::vector<CausticAim> aims;
  for (size_t l = 0; l < scene.lights.size(); ++l) {
    aims.push_back(aimAt(scene.lights[l], targets, bounds, hashKey(scene.render.seed, kAimStream, l)));
  }
  return aims;
}

PhotonBatches<IndirectPhoton> runPass(const Scene& scene, const TraceScene& tracer, MapKind kind,
                                      uint64_t pass, uint64_t total, const EmitOptions& options,
                                      uint64_t& emitted, PhotonTally& tally, PrefixCuts& cuts) {
  const SceneSphere bounds = tracer.boundingSphere();
  std::vector<SceneSphere> targets = kind == MapKind::Caustic ? specularTargets(scene)
                                                               : std::vector<SceneSphere>{};
  if (kind == MapKind::Caustic && targets.empty()) total = 0;
  const std::vector<CausticAim> aims = aimsOf(scene, bounds, targets);
  const std::vector<double> weights =
      photonWeights(scene, bounds, aims, kind == MapKind::Caustic,
                    options.reach[kind]);
  const std::vector<uint64_t> counts = splitByWeight(weights, total);
  tbb::enumerable_thread_specific<PhotonTally> tallies;
  const uint64_t stream = kind == MapKind::Caustic ? kCausticStream : kGlobalStream;
  PhotonBatches<IndirectPhoton> photons = runPhotonPass<IndirectPhoton>(
      weights, counts, options, &cuts, emitted, [&](const PhotonBatch& batch) {
        const Light& light = scene.lights[batch.light];
        const Color share = lightPower(light, bounds) / static_cast<float>(counts[batch.light]);
        const bool aimed = kind == MapKind::Caustic && aimsCausticPhotons(light);
        return [&, &light = light, share, aimed, aim = aims[batch.light], &t = tallies.local(),
                rng = Rng(hashKey(hashKey(scene.render.seed, pass), stream, batchStreamKey(batch))),
                scratch = std::vector<float>()](BatchAppender<IndirectPhoton>& out) mutable {
          PhotonRay r;
          Color power = share;
          if (aimed) {
            power *= sampleAimed(light, bounds, aim, rng, r, scratch);
          } else {
            // A spot's and an environment's caustic photons are the share of all their
            // photons whose path turns out L S+ D.
            float u1 = rng.uniform(), u2 = rng.uniform(), u3 = rng.uniform(), u4 = rng.uniform();
            r = emitterPhoton(light, bounds, u1, u2, u3, u4);
          }
          power *= r.weight;  // 1 but for an environment map's photons and a textured emitter's
          t.emitted += glm::dvec3(power);
          if (maxComponent(power) <= 0.0f) return;
          tracePhoton(scene, tracer, kind, Ray{r.origin, r.dir}, power, rng, out, t);
        };
      });
  for (const PhotonTally& t : tallies) tally += t;
  return photons;
}

}  // namespace

std::vector<SceneSphere> specularTargets(const Scene& scene) {
  auto specular = [&](int material) {
    return hasTracedLobe(makeBsdf(scene.materials[material], BsdfFamily::Radiometric,
                                 scene.photons.sampling));
  };
  std::vector<SceneSphere> out;
  for (const Sphere& s : scene.spheres) {
    // A hair larger, so a photon grazing the silhouette is not lost to rounding.
    if (specular(s.material)) out.push_back({s.center, s.radius * 1.001f});
  }
  for (const TriangleMesh& m : scene.meshes) {
    if (!specular(m.material) || m.positions.empty()) continue;
    Vec3 lo(kInf), hi(-kInf);
    for (const Vec3& p : m.positions) { lo = glm::min(lo, p); hi = glm::max(hi, p); }
    out.push_back({0.5f * (lo + hi), 0.5f * glm::length(hi - lo) * 1.001f + 1e-6f});
  }
  return out;
}

std::vector<uint64_t> splitPhysicalBudget(const Scene& scene, const TraceScene& tracer, bool caustic,
                                          uint64_t total, const std::vector<float>& reach) {
  const SceneSphere bounds = tracer.boundingSphere();
  const std::vector<SceneSphere> targets = caustic ? specularTargets(scene) : std::vector<SceneSphere>{};
  if (caustic && targets.empty()) return std::vector<uint64_t>(scene.lights.size(), 0);
  return splitByWeight(photonWeights(scene, bounds, aimsOf(scene, bounds, targets), caustic, reach), total);
}

void emitPhysicalPhotons(const Scene& scene, const TraceScene& tracer, uint64_t pass, const EmitOptions& options,
                         EmittedPhotons& out) {
  const MapCounts& budgets = options.budgets;
  for (MapKind k : {MapKind::Global, MapKind::Caustic}) {
    *out.batches.light(k) = runPass(scene, tracer, k, pass, options.maps[k] ? budgets[k] : 0, options, out.emitted[k],
                                    out.tally[k], out.cuts[k]);
  }
}

}  // namespace penumbra
