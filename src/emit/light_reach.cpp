// The reach pilot: first hits of a few photons per light, classified by the material
// rule of the map they would feed. Uses the emitters' own photon distribution.
#include "emit/light_reach.h"
#include "core/bsdf.h"
#include "core/color.h"
#include "core/light_sample.h"
#include "core/rng.h"
#include "emit/emit.h"
#include <tbb/parallel_for.h>

namespace penumbra {

bool reaches(const Scene& scene, int material, ReachRule rule) {
  const Material& m = scene.materials[material];
  switch (rule) {
    case ReachRule::Bouncing: return m.pR > 0.0f || m.pT > 0.0f;
    case ReachRule::Scattering:
      return maxComponent(albedoBsdf(makeBsdf(m, BsdfFamily::Radiometric, scene.photons.sampling))) > 0.0f;
    case ReachRule::Specular:
      return hasTracedLobe(makeBsdf(m, BsdfFamily::Radiometric, scene.photons.sampling));
  }
  return false;
}

namespace {

// Per emitting light, how many of `pilots` photons (stream `stream`, seeded by the
// scene's seed and the light's index) meet a surface at their first hit and pass
// `counts(rng, ray, surface)`; lights that emit nothing count 0.
template <class Counts>
std::vector<uint32_t> countPilots(const Scene& scene, const TraceScene& tracer, uint64_t stream, uint32_t pilots,
                                  uint8_t fields, Counts counts) {
  std::vector<uint32_t> n(scene.lights.size(), 0);
  const SceneSphere bounds = tracer.boundingSphere();
  tbb::parallel_for(size_t(0), scene.lights.size(), [&](size_t l) {
    const Light& light = scene.lights[l];
    if (!(maxComponent(light.radiance()) > 0.0f)) return;
    Rng rng(hashKey(scene.render.seed, stream, l));
    for (uint32_t i = 0; i < pilots; ++i) {
      const float u1 = rng.uniform(), u2 = rng.uniform(), u3 = rng.uniform(), u4 = rng.uniform();
      const PhotonRay r = emitterPhoton(light, bounds, u1, u2, u3, u4);
      const Ray ray{r.origin, r.dir};
      Hit hit;
      if (tracer.intersect(ray, hit)) n[l] += counts(rng, ray, tracer.surface(ray, hit, fields));
    }
  });
  return n;
}

// The emitters and the caustic aim use streams 1-5: the pilots have their own.
enum : uint64_t { kReachStream = 7, kReboundStream = 8 };

}  // namespace

std::vector<float> measureReach(const Scene& scene, const TraceScene& tracer, ReachRule rule,
                                uint32_t pilots) {
  std::vector<float> fraction(scene.lights.size(), 0.0f);
  if (pilots == 0) return fraction;
  // Classify each material once: the pilot's loop is rays only.
  std::vector<uint8_t> useful(scene.materials.size());
  for (size_t i = 0; i < useful.size(); ++i) useful[i] = reaches(scene, static_cast<int>(i), rule);
  auto stores = [&](Rng&, const Ray&, const SurfaceRecord& s) { return useful[s.material] != 0; };
  const std::vector<uint32_t> hits = countPilots(scene, tracer, kReachStream, pilots, kSurfaceGeometric, stores);
  for (size_t l = 0; l < hits.size(); ++l) fraction[l] = static_cast<float>(hits[l]) / static_cast<float>(pilots);
  return fraction;
}

float measureRebound(const Scene& scene, const TraceScene& tracer, uint32_t pilots) {
  uint32_t emitting = 0;
  for (const Light& light : scene.lights) emitting += maxComponent(light.radiance()) > 0.0f;
  if (pilots == 0 || emitting == 0) return 0.0f;
  auto lands = [&](Rng& rng, const Ray& ray, const SurfaceRecord& s) {
    const Bsdf bsdf = makeBsdf(scene.materials[s.material], BsdfFamily::Radiometric, scene.photons.sampling);
    const float uLobe = rng.uniform(), v1 = rng.uniform(), v2 = rng.uniform();
    const BsdfSample bs = sampleBsdf(bsdf, {s.ns, s.ng, s.frontFace}, -ray.dir, uLobe, v1, v2);
    if (!bs.valid || !(maxComponent(bs.weight) > 0.0f)) return false;
    Hit next;
    return tracer.intersect(Ray{spawnOrigin(s, bs.wi), bs.wi}, next);
  };
  const std::vector<uint32_t> landed = countPilots(scene, tracer, kReboundStream, pilots, kSurfaceShadingNormal, lands);
  uint64_t total = 0;
  for (uint32_t n : landed) total += n;
  return static_cast<float>(double(total) / (double(pilots) * emitting));
}

std::vector<double> reachWeighted(std::vector<double> weights, const std::vector<float>& reach) {
  if (reach.size() != weights.size()) return weights;
  for (size_t l = 0; l < weights.size(); ++l) weights[l] *= reach[l];
  return weights;
}

}  // namespace penumbra
