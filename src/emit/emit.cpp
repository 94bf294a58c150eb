// Shadow and indirect photon emission. Each batch draws from its own random
// stream keyed by (seed, map, batch index); per-thread buffers are merged in
// batch order, so the stored arrays do not depend on the thread count.
#include "emit/emit.h"
#include "core/color.h"
#include "core/optics.h"
#include "core/rng.h"
#include "core/sampling.h"
#include "emit/batch_buffers.h"

namespace penumbra {
namespace {

struct Batch {
  uint32_t light;
  uint64_t count;
};

std::vector<Batch> makeBatches(const std::vector<uint64_t>& perLight, uint32_t batchSize) {
  std::vector<Batch> batches;
  for (uint32_t l = 0; l < perLight.size(); ++l) {
    for (uint64_t done = 0; done < perLight[l]; done += batchSize) {
      batches.push_back({l, std::min<uint64_t>(batchSize, perLight[l] - done)});
    }
  }
  return batches;
}

// Follows one line from the light through every surface: the first hit is
// direct, all later ones are in shadow, opaque once anything opaque was crossed.
void traceShadowLine(const TraceScene& tracer, const Vec3& origin, const Vec3& dir, uint16_t light,
                     int maxHits, std::vector<ShadowPhoton>& out) {
  const std::vector<Material>& materials = tracer.scene().materials;
  Ray ray{origin, dir};
  ShadowKind kind = kDirect;
  for (int h = 0; h < maxHits; ++h) {
    Hit hit;
    if (!tracer.intersect(ray, hit)) return;
    SurfaceRecord s = tracer.surface(ray, hit, kSurfaceGeometric);
    out.push_back({s.position, encodeOctahedral(s.ng), light, kind});
    if (kind != kShadowOpaque) kind = materials[s.material].transparent ? kShadowGlass : kShadowOpaque;
    ray.origin = offsetRayOrigin(s.position, s.ng, dir);
  }
}

// One indirect photon path: stored at every hit (classic) or every hit after
// the first (density, whose direct part comes from the Phong term instead).
void traceIndirectPath(const Scene& scene, const TraceScene& tracer, Ray ray, Color power, Rng& rng,
                       bool storeFirstHit, std::vector<IndirectPhoton>& out) {
  const PhotonSettings& ps = scene.photons;
  for (int bounce = 0; bounce <= ps.maxBounces; ++bounce) {
    Hit hit;
    if (!tracer.intersect(ray, hit)) return;
    SurfaceRecord s = tracer.surface(ray, hit, kSurfaceShadingNormal);
    const Material& m = scene.materials[s.material];
    if (bounce > 0 || storeFirstHit) {
      out.push_back({s.position, power, encodeOctahedral(ray.dir), encodeOctahedral(s.ng)});
    }
    // Russian roulette: the survival probability already carries the surface's
    // average reflectance, so a survivor keeps its power level and only takes
    // on the surface's hue (colour / mean colour).
    float xi = rng.uniform();
    float u1 = rng.uniform(), u2 = rng.uniform();
    Vec3 dir;
    if (xi < m.pR) {
      // A Lambertian surface scatters with density cos(theta) / pi. Cosine
      // sampling draws exactly that; uniform sampling (pdf 1 / 2 pi, the report's)
      // carries the ratio 2 cos(theta) as a weight, so both converge to the same
      // light and differ only in noise.
      bool cosine = ps.sampling == HemisphereSampling::Cosine;
      Vec3 local = cosine ? cosineHemisphere(u1, u2) : uniformHemisphere(u1, u2);
      dir = toWorld(local, s.ng);
      float mean = meanOf(m.diffuse);
      power *= mean > 0.0f ? m.diffuse / mean : Color(0.0f);
      if (!cosine) power *= 2.0f * local.z;
    } else if (xi < m.pR + m.pT) {
      float eta = s.frontFace ? 1.0f / m.ior : m.ior;
      bool refracted = refract(ray.dir, s.ns, eta, dir);
      if (!refracted) dir = reflect(ray.dir, s.ns);  // total internal reflection
      float mean = meanOf(m.tint);
      // The tint filters light entering the material, as on camera rays.
      if (refracted && s.frontFace) power *= mean > 0.0f ? m.tint / mean : Color(0.0f);
    } else {
      return;  // absorbed
    }
    if (maxComponent(power) <= 0.0f) return;
    ray = Ray{offsetRayOrigin(s.position, s.ng, dir), dir};
  }
}

}  // namespace

std::vector<uint64_t> splitBudget(const Scene& scene, uint64_t total) {
  std::vector<double> power(scene.lights.size(), 0.0);
  double sum = 0.0;
  for (size_t l = 0; l < scene.lights.size(); ++l) {
    if (scene.lights[l].type != LightType::Point) continue;
    power[l] = std::max(0.0f, luminance(scene.lights[l].radiance()));
    sum += power[l];
  }
  std::vector<uint64_t> count(power.size(), 0);
  if (sum <= 0.0 || total == 0) return count;
  // Largest remainder: floor every share, then hand out what is left by the
  // size of the dropped fractions (ties to the lower light index).
  std::vector<std::pair<double, size_t>> remainders;
  uint64_t given = 0;
  for (size_t l = 0; l < power.size(); ++l) {
    double share = total * power[l] / sum;
    count[l] = static_cast<uint64_t>(share);
    given += count[l];
    if (power[l] > 0.0) remainders.push_back({share - count[l], l});
  }
  std::stable_sort(remainders.begin(), remainders.end(),
                   [](const auto& a, const auto& b) { return a.first > b.first; });
  for (size_t i = 0; given < total && i < remainders.size(); ++i, ++given) ++count[remainders[i].second];
  return count;
}

PhotonMaps emitPhotons(const Scene& scene, const TraceScene& tracer, const EmitOptions& options) {
  PhotonMaps maps;
  const PhotonSettings& ps = scene.photons;
  const uint64_t seed = scene.render.seed;
  enum : uint64_t { kShadowStream = 1, kIndirectStream = 2 };

  // Without the gate (or without shadows) nobody reads the shadow map: do not pay for it.
  bool wantShadowMap = options.shadowMap && ps.gate && scene.render.shadows;
  std::vector<uint64_t> shadowCounts = splitBudget(scene, wantShadowMap ? ps.shadowPhotons : 0);
  std::vector<Batch> shadowBatches = makeBatches(shadowCounts, options.batchSize);
  BatchBuffers<ShadowPhoton> shadowBuffers;
  tbb::parallel_for(size_t(0), shadowBatches.size(), [&](size_t b) {
    const Batch& batch = shadowBatches[b];
    const Light& light = scene.lights[batch.light];
    Rng rng(hashKey(seed, kShadowStream, b));
    auto& local = shadowBuffers.local();
    for (uint64_t i = 0; i < batch.count; ++i) {
      float u1 = rng.uniform(), u2 = rng.uniform();
      traceShadowLine(tracer, light.position, uniformSphere(u1, u2), static_cast<uint16_t>(batch.light),
                      options.maxHitsPerLine, local.photons);
    }
    local.endBatch(b);
  });
  maps.shadow = shadowBuffers.merge();

  std::vector<uint64_t> indirectCounts = splitBudget(scene, ps.indirectPhotons);
  std::vector<Batch> indirectBatches = makeBatches(indirectCounts, options.batchSize);
  bool storeFirstHit = ps.estimator == IndirectEstimator::Classic;
  BatchBuffers<IndirectPhoton> indirectBuffers;
  tbb::parallel_for(size_t(0), indirectBatches.size(), [&](size_t b) {
    const Batch& batch = indirectBatches[b];
    const Light& light = scene.lights[batch.light];
    // Each photon carries an equal share of the light's flux 4 pi I.
    Color power = light.radiance() * (4.0f * kPi / static_cast<float>(indirectCounts[batch.light]));
    Rng rng(hashKey(seed, kIndirectStream, b));
    auto& local = indirectBuffers.local();
    for (uint64_t i = 0; i < batch.count; ++i) {
      float u1 = rng.uniform(), u2 = rng.uniform();
      traceIndirectPath(scene, tracer, Ray{light.position, uniformSphere(u1, u2)}, power, rng,
                        storeFirstHit, local.photons);
    }
    local.endBatch(b);
  });
  maps.indirect = indirectBuffers.merge();

  for (uint64_t c : shadowCounts) maps.emittedShadow += c;
  for (uint64_t c : indirectCounts) maps.emittedIndirect += c;
  double intensity = 0.0;
  for (const Light& l : scene.lights) {
    if (l.type == LightType::Point) intensity += luminance(l.radiance());
  }
  if (maps.emittedIndirect > 0 && intensity > 0.0) {
    maps.classicScale = static_cast<float>(maps.emittedIndirect / (4.0 * kPi * intensity));
  }
  return maps;
}

}  // namespace penumbra
