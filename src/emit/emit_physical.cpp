// Physical photon emission. The global pass shoots photons from every light in
// proportion to its power; the caustic pass aims them at the specular objects'
// bounding spheres (Jensen's projection maps) and keeps only L S+ D paths; in a
// scene with a medium the volume pass stores photons scattered in media.
#include "emit/emit_physical.h"
#include "emit/photon_pass.h"
#include "core/bsdf.h"
#include "core/light_sample.h"
#include "core/rng.h"
#include "core/sampling.h"
#include "emit/batch_buffers.h"
#include "emit/budget.h"
#include "emit/caustic_aim.h"
#include "emit/medium_walk.h"
#include "core/media/phase_function.h"
#include <tbb/parallel_for.h>
#include <tbb/enumerable_thread_specific.h>
#include <type_traits>

namespace penumbra {

namespace {

enum : uint64_t { kGlobalStream = 3, kCausticStream = 4, kVolumeStream = 6 };

// Follows one photon; stores it as the pass dictates and plays Russian roulette by
// each sampled weight. kMedia (a scene with a medium, decided once per pass): the
// photon also flies through media, where a collision scatters it by the phase
// function after the albedo roulette; the global pass counts that as a diffuse bounce,
// the caustic pass ends there, the volume pass (Photon = VolumePhoton) stores it when
// an event came before. Without media the code is the surface-only walk, as it was.
template <bool kMedia, class Photon>
void tracePhoton(const Scene& scene, const TraceScene& tracer, MapKind pass, Ray ray, int medium, Color power,
                 Rng& rng, BatchAppender<Photon>& out, PhotonTally& tally) {
  constexpr bool kVolume = std::is_same_v<Photon, VolumePhoton>;
  const PhotonSettings& ps = scene.photons;
  int diffuseBounces = 0, specularBounces = 0;
  for (int bounce = 0;; ++bounce) {
    Hit hit;
    if constexpr (kMedia) {
      const FlightEnd f = flyToEvent(scene, tracer, ray, medium, power, rng, tally);
      if (f.kind == FlightEnd::Escaped) {
        tally.escaped += glm::dvec3(power);
        return;
      }
      if (f.kind == FlightEnd::Absorbed) return;
      if (f.kind == FlightEnd::Lost || bounce > ps.maxBounces) {
        tally.capped += glm::dvec3(power);
        return;
      }
      if (f.kind == FlightEnd::Collision) {
        if (pass == MapKind::Caustic) {  // L S+ D paths only
          tally.absorbed += glm::dvec3(power);
          return;
        }
        const float uRr = rng.uniform(), u1 = rng.uniform(), u2 = rng.uniform();
        if (!surviveRoulette(power, f.weight, uRr, tally)) return;
        if constexpr (kVolume) {
          if (bounce > 0) {  // L -> V is the camera's single scattering
            out.push_back({f.position, power, encodeOctahedral(ray.dir), medium});
            tally.stored[pass] += glm::dvec3(power);
          }
        }
        ++diffuseBounces;
        ray = Ray{f.position, sampleHenyeyGreenstein(scene.media[medium].g, ray.dir, u1, u2).dir};
        continue;
      }
      hit = f.hit;
    } else if (!tracer.intersect(ray, hit)) {
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
    if constexpr (!kVolume) {
      if (hasGatheredLobe(bsdf)) {  // where a camera path reads the maps
        bool store = pass == MapKind::Global ? diffuseBounces > 0 : specularBounces > 0;
        if (store) {
          out.push_back({s.position, power, encodeOctahedral(ray.dir), encodeOctahedral(s.ng)});
          tally.stored[pass] += glm::dvec3(power);
        }
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
    if (!surviveRoulette(power, bs.weight, uRr, tally)) return;
    if (delta) ++specularBounces; else ++diffuseBounces;
    if constexpr (kMedia) medium = tracer.mediumBeyond(hit, s, bs.wi, medium);
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

template <bool kMedia, class Photon>
PhotonBatches<Photon> runPass(const Scene& scene, const TraceScene& tracer, MapKind kind, uint64_t pass,
                              uint64_t total, const EmitOptions& options, uint64_t& emitted, PhotonTally& tally,
                              PrefixCuts& cuts) {
  const SceneSphere bounds = tracer.boundingSphere();
  std::vector<SceneSphere> targets = kind == MapKind::Caustic ? specularTargets(scene)
                                                               : std::vector<SceneSphere>{};
  if (kind == MapKind::Caustic && targets.empty()) total = 0;
  const std::vector<CausticAim> aims = aimsOf(scene, bounds, targets);
  // The volume pass splits by power alone: every light's photons can scatter in a medium.
  const std::vector<double> weights =
      photonWeights(scene, bounds, aims, kind == MapKind::Caustic,
                    kind == MapKind::Volume ? std::vector<float>{} : options.reach[kind]);
  const std::vector<uint64_t> counts = splitByWeight(weights, total);
  tbb::enumerable_thread_specific<PhotonTally> tallies;
  const uint64_t stream = kind == MapKind::Caustic ? kCausticStream
                          : kind == MapKind::Volume ? kVolumeStream
                                                    : kGlobalStream;
  PhotonBatches<Photon> photons = runPhotonPass<Photon>(
      weights, counts, options, &cuts, emitted, [&](const PhotonBatch& batch) {
        const Light& light = scene.lights[batch.light];
        const Color share = lightPower(light, bounds) / static_cast<float>(counts[batch.light]);
        const bool aimed = kind == MapKind::Caustic && aimsCausticPhotons(light);
        const int medium = kMedia ? startMedium(scene, light) : kNoMedium;
        const Color arriving = kMedia ? arrivingShare(scene, light, medium) : Color(1.0f);
        return [&, &light = light, share, aimed, medium, arriving, aim = aims[batch.light], &t = tallies.local(),
                rng = Rng(hashKey(hashKey(scene.render.seed, pass), stream, batchStreamKey(batch))),
                scratch = std::vector<float>()](BatchAppender<Photon>& out) mutable {
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
          if constexpr (kMedia) {
            t.absorbed += glm::dvec3(power) - glm::dvec3(power * arriving);
            power *= arriving;
          }
          if (maxComponent(power) <= 0.0f) return;
          tracePhoton<kMedia>(scene, tracer, kind, Ray{r.origin, r.dir}, medium, power, rng, out, t);
        };
      });
  for (const PhotonTally& t : tallies) tally += t;
  return photons;
}

template <bool kMedia>
void emitPasses(const Scene& scene, const TraceScene& tracer, uint64_t pass, const EmitOptions& options,
                EmittedPhotons& out) {
  const MapCounts& budgets = options.budgets;
  for (MapKind k : {MapKind::Global, MapKind::Caustic}) {
    *out.batches.light(k) = runPass<kMedia, IndirectPhoton>(scene, tracer, k, pass, options.maps[k] ? budgets[k] : 0,
                                                            options, out.emitted[k], out.tally[k], out.cuts[k]);
  }
  if constexpr (kMedia) {
    const MapKind v = MapKind::Volume;
    out.batches.get<MapKind::Volume>() = runPass<true, VolumePhoton>(
        scene, tracer, v, pass, options.maps[v] ? budgets[v] : 0, options, out.emitted[v], out.tally[v], out.cuts[v]);
  }
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
  if (scene.hasMedia()) emitPasses<true>(scene, tracer, pass, options, out);
  else emitPasses<false>(scene, tracer, pass, options, out);
}

}  // namespace penumbra
