// Light visibility through the ambiguity gate, and the ambient/indirect term.
// Only the penumbra (photons disagree) pays for a real shadow ray.
#include "trace/light_visibility.h"
#include "gather/photon_map.h"
#include "core/bsdf.h"
#include "core/light_sample.h"
#include "trace/medium_shadow.h"

namespace penumbra {

ThreadState::ThreadState() : scratch(std::make_unique<GatherScratch>()) {}
ThreadState::~ThreadState() = default;
ThreadState::ThreadState(ThreadState&&) noexcept = default;

namespace {

// Transmittance along a shadow ray. Opaque scenes need one occlusion query;
// with glass, walk the segment and filter by the tint of every surface entered
// (Whitted's tinted shadows: cheap, no caustic focusing). A walk that meets the
// light's own surface has arrived.
Color shadowTransmittance(const ShadingContext& ctx, const SurfaceRecord& s, uint32_t lightIndex,
                          const LightIncidence& in, ThreadState& ts) {
  ++ts.counts.shadow;
  Ray ray;
  if (!shadowRayTo(s, in, ray)) return Color(1.0f);  // the origin is already at the light
  if (ts.shadingPoint == 1 && lightIndex < 32 && ((ts.knownShadows >> lightIndex) & 1u)) {
    // This very ray was traced ahead in a packet (tracePrimaryShadows).
    return ((ts.blockedShadows >> lightIndex) & 1u) ? Color(0.0f) : Color(1.0f);
  }
  const bool finite = std::isfinite(in.distance);
  const bool tinted = ctx.hasGlass && ctx.choices.integrator->glass == GlassShadows::Tint;
  // Opaque surfaces (glass too, in the physical model) block; media attenuate
  // (trace/medium_shadow.h).
  if (!tinted) return lightTransmittance(ctx, ray, in.margin, lightIndex, ts.medium, ts);
  Color t(1.0f);
  for (int crossing = 0; crossing < 32; ++crossing) {
    Hit hit;
    if (!ctx.tracer.intersect(ray, hit)) return t;
    SurfaceRecord h = ctx.tracer.surface(ray, hit, kSurfaceGeometric);
    const Material& m = ctx.scene.materials[h.material];
    if (m.light == static_cast<int>(lightIndex)) return t;  // reached the light itself
    if (!m.transparent) return Color(0.0f);
    if (h.frontFace) t *= m.tint;
    if (maxComponent(t) < ctx.scene.render.minWeight) return Color(0.0f);
    ray.origin = spawnOrigin(h, ray.dir);
    if (finite) ray.tMax = glm::dot(in.point - ray.origin, ray.dir) - in.margin;
    if (ray.tMax <= 0.0f) return t;
  }
  return Color(0.0f);
}

}  // namespace

bool shadowRayTo(const SurfaceRecord& s, const LightIncidence& in, Ray& ray) {
  ray = Ray{spawnOrigin(s, in.wi), in.wi};
  // A point on the edge where two faces meet (a room's corner) may sit a rounding
  // error behind the other face and see it at t ~ 0: occluders nearer than a few
  // times the point's own error cannot be told from it, so they do not shadow.
  ray.tMin = 4.0f * s.spread;
  if (std::isfinite(in.distance)) {
    // Aim from the lifted origin at the sample itself (pbrt's SpawnRayTo): measured
    // from the shading point instead, a lift of e along n would move the ray's
    // crossing of the light's plane by e / cos, more than the margin at grazing angles.
    const Vec3 d = in.point - ray.origin;
    const float len = glm::length(d);
    if (!(len > in.margin)) return false;
    ray.dir = d / len;
    ray.tMax = len - in.margin;
  }
  return true;
}

GateParams gateParamsFor(const Scene& scene, GlassShadows glass) {
  GateParams params;
  params.k = scene.photons.kShadow;
  params.maxRadius = scene.photons.maxRadius;
  // A small k cannot muster the default quorum; let every neighbour count.
  params.minVoters = std::min(params.minVoters, params.k);
  params.glassBlocks = glass == GlassShadows::Block;
  return params;
}

const CachedAnswer* lookupAt(const ShadingContext& ctx, const SurfaceRecord& s,
                             CachedAnswer& storage, ThreadState& ts) {
  if (!ctx.lookup) return nullptr;
  ++ts.counts.cacheLookups;
  storage = ctx.lookup->find(s.position, s.ng, !s.frontFace);
  if (ctx.gateLookup && ctx.gateLookup != ctx.lookup) storage.verdicts = ctx.gateLookup->find(s.position, s.ng, !s.frontFace).verdicts;
  return &storage;
}

GateVerdict gateVerdict(const ShadingContext& ctx, const SurfaceRecord& s, uint32_t lightIndex,
                        const CachedAnswer* cached, ThreadState& ts, std::string* note) {
  const ShadowPhotonMap* shadowMap = ctx.maps.get<MapKind::Shadow>();
  if (!ctx.choices.gate || !shadowMap || !shadowMap->hasPhotons(lightIndex)) return GateVerdict::Mixed;
  ++ts.counts.gateQueries;
  GateVerdict v;
  const bool precomputed = cached && ctx.gateLookup && ctx.gateLookup->hasGate();
  if (precomputed) {
    // The precomputed verdict of the point's cell; no cell there: a shadow ray.
    v = cached->verdicts ? static_cast<GateVerdict>(cached->verdicts[lightIndex]) : GateVerdict::Mixed;
  } else {
    const GateParams params = gateParamsFor(ctx.scene, ctx.choices.integrator->glass);
    v = shadowMap->classify(s.position, s.ng, lightIndex, params, *ts.scratch, !s.frontFace);
  }
  // Shadowed means every voter sits behind something opaque; photons behind
  // glass alone make the vote Mixed, since only a ray can measure the tint.
  const char* how = precomputed ? "gate (precomputed): " : "gate: ";
  if (v == GateVerdict::Lit) {
    ++ts.counts.gateLit;
    if (note) *note = std::string(how) + "lit";
  } else if (v == GateVerdict::Shadowed) {
    ++ts.counts.gateShadowed;
    if (note) *note = std::string(how) + "shadowed";
  } else {
    ++ts.counts.gateMixed;
    if (note) *note = std::string(how) + "mixed, shadow ray";
  }
  return v;
}

const uint8_t* gateStrata(const ShadingContext& ctx, uint32_t li, const CachedAnswer* cached) {
  if (!cached || !cached->verdicts || !ctx.choices.gate || !ctx.gateLookup || !ctx.gateLookup->hasGate()) return nullptr;
  if (ctx.gateLookup->strataOf(li) <= 1) return nullptr;
  return cached->verdicts;
}

Color litClosedForm(const ShadingContext& ctx, const SurfaceRecord& s, uint32_t li,
                    const LightSampler& sampler, const Bsdf& bsdf, bool asked,
                    const CachedAnswer* cached, ThreadState& ts, std::string* note) {
  // No closed form (a delta light, a sphere cut by the horizon, a large mesh): the
  // samples, all of which missed, were the estimate, and 0 is its unbiased value.
  if (isDeltaLight(*sampler.light)) return Color(0.0f);
  // Without a gate for this light its verdict is mixed: not worth a closed form.
  const ShadowPhotonMap* shadowMap = ctx.maps.get<MapKind::Shadow>();
  if (!asked && !(ctx.choices.gate && shadowMap && shadowMap->hasPhotons(li))) return Color(0.0f);
  const Color kd = lambertCoefficient(bsdf);
  Color E;
  if (!(maxComponent(kd) > 0.0f) || !unoccludedIrradiance(sampler, s.ns, s.ng, E) || !(maxComponent(E) > 0.0f))
    return Color(0.0f);
  if (!asked && gateVerdict(ctx, s, li, cached, ts, note) != GateVerdict::Lit) return Color(0.0f);
  return kd * E;
}

Color shadowRay(const ShadingContext& ctx, const SurfaceRecord& s, uint32_t lightIndex,
                const LightIncidence& in, ThreadState& ts) {
  Color t = shadowTransmittance(ctx, s, lightIndex, in, ts);
  if (ts.recorder) {
    // The shadow ray joins the ray tree under the ray whose hit it lights.
    RayRecord r;
    r.kind = "shadow";
    r.parent = ts.currentRecord;
    r.depth = ts.currentRecord >= 0 ? (*ts.recorder)[ts.currentRecord].depth + 1 : 0;
    r.origin = spawnOrigin(s, in.wi);
    r.dir = in.wi;
    r.hit = maxComponent(t) < 1.0f;  // blocked or filtered on the way to the light
    r.contribution = t;
    r.note = "light " + std::to_string(lightIndex) + (r.hit ? (maxComponent(t) > 0.0f ? ": through glass" : ": blocked") : ": clear");
    ts.recorder->push_back(r);
  }
  return t;
}

Color litMediaTransmittance(const ShadingContext& ctx, const SurfaceRecord& s, const LightIncidence& in,
                            ThreadState& ts) {
  Ray ray;
  if (!shadowRayTo(s, in, ray)) return Color(1.0f);
  return segmentTransmittance(ctx, ray, ray.tMax + in.margin, ts.medium, ts);
}

Color ambientTerm(const ShadingContext& ctx, const SurfaceRecord& s, const Material& m,
                  const CachedAnswer* cached, ThreadState& ts) {
  const IndirectPhotonMap* map = ctx.maps.get<MapKind::Indirect>();
  if (!map || map->empty()) return m.ambient * ctx.scene.render.ambient;
  const PhotonSettings& ps = ctx.scene.photons;
  const PhotonGather gather = ctx.gathers[MapKind::Indirect];
  if (cached && ctx.lookup->indirectKind() != CachedIndirect::None) {
    if (cached->hasIndirect) {
      return ctx.lookup->indirectKind() == CachedIndirect::Density
                 ? m.diffuse * cached->indirect
                 : m.ambient * cached->indirect * ctx.classicScale;
    }
    // No cell near the point: its own cell's estimate, computed once and kept (a
    // gather per point here was a large share of the showcase's render).
    ++ts.counts.cacheFallbacks;
    const Color v = ctx.lookup->lazyIndirect(*map, s.position, s.ng, *ts.scratch);
    return ctx.lookup->indirectKind() == CachedIndirect::Density ? m.diffuse * v
                                                                  : m.ambient * v * ctx.classicScale;
  }
  ++ts.counts.gatherQueries;
  if (ps.estimator == IndirectEstimator::Density) {
    // Irradiance from the cone-filtered density, reflected like direct light
    // (k_d E), so direct and indirect share the same units.
    auto e = map->density(s.position, s.ng, gather.k, gather.maxRadius, *ts.scratch);
    ts.counts.gatherNeighbours += static_cast<uint64_t>(e.found);
    return m.diffuse * e.value;
  }
  // Classic (the report's): the cone-weighted sum of photon colours over the
  // photon count replaces the global ambient light; the material's ambient
  // colour still filters it.
  auto e = map->classic(s.position, s.ng, gather.k, gather.maxRadius, *ts.scratch);
  ts.counts.gatherNeighbours += static_cast<uint64_t>(e.found);
  return m.ambient * e.value * ctx.classicScale;
}

// Shadow packets: the same shadow rays shadowTransmittance builds (shadowRayTo from the
// same surface record and light sample), only traced 16 at a time.

uint32_t packetShadowLights(const ShadingContext& ctx, bool direct) {
  const Scene& scene = ctx.scene;
  const bool tinted = ctx.hasGlass && ctx.choices.integrator->glass == GlassShadows::Tint;
  // With media a shadow ray carries a transmittance, not a bit: those scenes cast
  // their rays one by one (packets would only save the occlusion half of the walk).
  if (!direct || !ctx.choices.shadows || tinted || scene.hasMedia()) return 0;
  uint32_t mask = 0;
  for (uint32_t li = 0; li < scene.lights.size() && li < 32; ++li) {
    const Light& light = scene.lights[li];
    if (!isDeltaLight(light) || maxComponent(light.radiance()) <= 0.0f) continue;
    // As gateVerdict: with a gate for this light the verdict, not the ray, comes first.
    const ShadowPhotonMap* shadowMap = ctx.maps.get<MapKind::Shadow>();
    const bool gated = ctx.choices.gate && shadowMap && shadowMap->hasPhotons(li);
    if (!gated) mask |= 1u << li;
  }
  return mask;
}

void tracePrimaryShadows(const ShadingContext& ctx, uint32_t lights, const Ray* rays,
                         const Hit* hits, int n, uint32_t* known, uint32_t* blocked,
                         PrimaryShadowScratch& scratch) {
  for (int i = 0; i < n; ++i) known[i] = blocked[i] = 0;
  if (lights == 0) return;
  const Scene& scene = ctx.scene;
  scratch.rays.resize(static_cast<size_t>(n));
  scratch.owner.resize(static_cast<size_t>(n));
  scratch.blocked.resize(static_cast<size_t>(n));
  for (uint32_t li = 0; li < scene.lights.size() && li < 32; ++li) {
    if (!((lights >> li) & 1u)) continue;
    const Light& light = scene.lights[li];
    int count = 0;
    for (int i = 0; i < n; ++i) {
      if (!hits[i].valid()) continue;
      const Material& m = scene.materials[ctx.tracer.materialOf(hits[i])];
      if (maxComponent(m.emission) > 0.0f && !m.emitterShades) continue;  // a light's surface only glows
      if (!ctx.choices.integrator->shadesDirect(scene, m)) continue;
      // The record the integrators build (position, normals and error bounds do not
      // depend on the uv fields).
      const SurfaceRecord s = ctx.tracer.surface(rays[i], hits[i], kSurfaceShadingNormal);
      // A delta light's one sample, as directFromLight draws it.
      const Vec2 u = deltaLightSample();
      const LightIncidence in = sampleLight(prepareLight(light, s.position), u.x, u.y);
      if (!facesLight(s, in)) continue;
      known[i] |= 1u << li;
      if (!shadowRayTo(s, in, scratch.rays[static_cast<size_t>(count)])) continue;  // at the light: clear
      scratch.owner[static_cast<size_t>(count++)] = i;
    }
    ctx.tracer.occludedPacket(scratch.rays.data(), count, scratch.blocked.data());
    for (int j = 0; j < count; ++j) {
      if (scratch.blocked[static_cast<size_t>(j)]) blocked[scratch.owner[static_cast<size_t>(j)]] |= 1u << li;
    }
  }
}

}  // namespace penumbra
