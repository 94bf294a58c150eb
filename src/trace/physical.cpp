// Physical shading. At a diffuse or glossy hit: direct light from every light by
// shadow rays (opaque and glass both block), plus the caustic and global photon
// estimates; mirror and glass lobes are followed by rays, weighted by their
// reflectance and Fresnel (both branches of glass, as the Whitted tracer does).
// In scenes with media the ray's medium travels with it (trace/medium_path.h).
#include "trace/physical.h"
#include "core/bsdf.h"
#include "core/lights/environment_map.h"
#include "core/light_sample.h"
#include "core/optics.h"
#include "core/rng.h"
#include "gather/radiance_estimate.h"
#include "gather/umbra_gather.h"
#include "trace/environment_light.h"
#include "trace/glass_split.h"
#include "trace/light_visibility.h"
#include "trace/medium_path.h"
#include "trace/normal_map.h"
#include "trace/texture_lookup.h"

namespace penumbra {
namespace {

enum : uint64_t { kNarrowStream = 0x6e6172726f77ull };  // "narrow": apart from the light samples'

Color directLight(const ShadingContext& ctx, const SurfaceRecord& s, const Bsdf& bsdf,
                  const BsdfFrame& frame, const Vec3& wo, const CachedAnswer* cached,
                  ThreadState& ts, std::string* note) {
  Color sum(0.0f);
  const auto& lights = ctx.scene.lights;
  for (uint32_t li = 0; li < lights.size(); ++li) {
    if (maxComponent(lights[li].radiance()) <= 0.0f) continue;
    std::string one;
    if (lightTraits(lights[li]).direct == DirectSampling::EnvironmentMis) {
      sum += directFromEnvironment(ctx, s, li, bsdf, frame, wo, ts, note ? &one : nullptr);
    } else {
      sum += directFromLight(
        ctx, s, li, cached, ts, note ? &one : nullptr, bsdf, frame, wo,
        [](const Color& t, const Color& f, const LightIncidence& in) { return t * f * in.radiance; });
    }
    if (note && !one.empty()) *note += (note->empty() ? "" : "; ") + one;
  }
  return sum;
}

// `throughput`: the camera path's weight at this point, which weighs the estimate's
// smoothing bias into the sample's (ThreadState::smoothing) when the gather probes it.
template <MapKind K>
Color photonTerm(const ShadingContext& ctx, MapKindTag<K> kind, const SurfaceRecord& s, const Bsdf& bsdf,
                 const BsdfFrame& frame, const Vec3& wo, const CachedAnswer* cached, const Color& throughput,
                 ThreadState& ts, bool unlit = false) {
  const IndirectPhotonMap* map = ctx.maps.get<K>();
  if (!map || map->empty() || !hasGatheredLobe(bsdf)) return Color(0.0f);
  // The cache holds irradiance / pi: it answers a Lambertian BSDF exactly; a glossy
  // lobe needs the photons' directions, so it gathers.
  if (cached && ctx.lookup->indirectKind() == CachedIndirect::Irradiance &&
      bsdf.type == BsdfType::Opaque && !(bsdfFlags(bsdf) & kBsdfGlossy)) {
    if (cached->hasIndirect) return (1.0f - bsdf.kr) * bsdf.diffuse * cached->indirect;
    ++ts.counts.cacheFallbacks;  // no cell near: its own cell's estimate, kept
    return (1.0f - bsdf.kr) * bsdf.diffuse * ctx.lookup->lazyIndirect(*map, s.position, s.ng, *ts.scratch);
  }
  ++ts.counts.gatherQueries;
  const PhotonGather gather = unlit ? umbraGather(ctx.gathers[kind]) : ctx.gathers[kind];
  RadianceEstimate e = photonRadiance(*map, gatheredPart(bsdf), frame, s.position, wo, gather, *ts.scratch);
  ts.counts.gatherNeighbours += static_cast<uint64_t>(e.found);
  if (gather.probeSmoothing) ts.smoothing += throughput * e.smoothing;
  return e.value;
}


// The ray's first hit shaded (or what a miss sees), `medium` the medium it arrived in.
Color shadeSurface(const ShadingContext& ctx, const Ray& ray, const Hit* found, int depth, const Color& throughput,
                   RayKind kind, uint8_t terms, int parentRecord, ThreadState& ts, int medium);

}  // namespace

Color tracePhysical(const ShadingContext& ctx, const Ray& ray, int depth, const Color& throughput,
                    RayKind kind, uint8_t terms, int parentRecord, ThreadState& ts, int medium) {
  Hit hit;
  const bool found = ctx.tracer.intersect(ray, hit);
  return tracePhysicalHit(ctx, ray, found ? &hit : nullptr, depth, throughput, kind, terms,
                          parentRecord, ts, medium);
}

Color tracePhysicalHit(const ShadingContext& ctx, const Ray& ray, const Hit* found, int depth,
                       const Color& throughput, RayKind kind, uint8_t terms, int parentRecord,
                       ThreadState& ts, int medium) {
  if (!ctx.scene.hasMedia()) return shadeSurface(ctx, ray, found, depth, throughput, kind, terms, parentRecord, ts, kNoMedium);
  // What the media add on the way, and what they let through of what lies beyond.
  const MediumStretch st = traceMediumStretch(ctx, ray, found ? found->t : kInf, medium, terms, ts);
  if (!(maxComponent(st.transmittance) > 0.0f)) {  // opaque fog: nothing beyond to shade (and no inf x 0)
    countRay(kind, ts.counts);
    --ts.raysLeft;
    return st.radiance;
  }
  const Color beyond = shadeSurface(ctx, ray, found, depth, throughput * st.transmittance, kind, terms,
                                    parentRecord, ts, st.medium);
  return st.radiance + st.transmittance * beyond;
}

namespace {

Color shadeSurface(const ShadingContext& ctx, const Ray& ray, const Hit* found, int depth, const Color& throughput,
                   RayKind kind, uint8_t terms, int parentRecord, ThreadState& ts, int medium) {
  countRay(kind, ts.counts);
  --ts.raysLeft;
  int recIndex = ts.recorder ? beginRecord(ts, kind, ray, depth, throughput, parentRecord) : -1;

  if (!found) {
    // The environment is a light seen directly (as an emitter's glow, so a narrow
    // lobe's ray, whose lights are sampled, leaves it out); otherwise the background.
    const bool env = missSeesEnvironment(ctx.scene, kind);
    Color c = (terms & (env ? kTermEmitters : kTermMissed)) ? missRadiance(ctx.scene, ray.dir, kind) : Color(0.0f);
    if (recIndex >= 0) (*ts.recorder)[recIndex].contribution = throughput * c;
    return c;
  }
  const Hit& hit = *found;
  const Material& m = ctx.scene.materials[ctx.tracer.materialOf(hit)];
  const bool textured = readsUv(m);
  SurfaceRecord s = ctx.tracer.surface(ray, hit, textured ? kSurfaceAll : kSurfaceShadingNormal);
  const float footprint = hit.t * ctx.pixelSpread;
  // An area light seen by the camera or through mirrors and glass (diffuse surfaces
  // sample it directly instead): part of the direct term.
  const Color glow = emitterGlow(ctx, m, s, footprint, !(terms & kTermEmitters));
  if (maxComponent(m.emission) > 0.0f && !m.emitterShades) {
    if (recIndex >= 0) endRecord(ts, recIndex, hit, s, m, throughput * glow, "emitter");
    return glow;
  }
  ++ts.shadingPoint;
  // The vertex colour multiplies the base colour, as the texture below does.
  Bsdf bsdf = makeBsdf(m, BsdfFamily::Radiometric, ctx.scene.photons.sampling, Color(ctx.tracer.vertexColor(hit)));
  const Vec3 interpolated = s.ns;
  MetalRough mr{m.metallic, m.roughness};
  if (textured && ctx.textures) {
    // A texture is the diffuse albedo's (base colour's) map: multiplied in, or added
    // and kept <= 1; a metallic-roughness map scales those factors.
    applyNormalMap(m, *ctx.textures, ctx.tracer, hit, footprint, ray.dir, s);
    if (m.texture >= 0) {
      Color texel = ctx.textures->lookup(m.texture, s, footprint, m.uvTransform());
      bsdf.diffuse = m.textureBlend == TextureBlend::Multiply
                         ? bsdf.diffuse * texel
                         : glm::min(bsdf.diffuse + texel, Color(1.0f) - bsdf.specular);
    }
    if (m.metalRoughTexture >= 0) {
      mr = metalRoughAt(m, *ctx.textures, s, footprint);
      setMetalRough(bsdf, BsdfFamily::Radiometric, bsdf.diffuse, mr.metallic, mr.roughness);
    }
  }
  // The radiometric family keeps the base colour as the diffuse term.
  if (recIndex >= 0) recordSurface(ts, recIndex, s, interpolated, m, {bsdf.diffuse, mr.metallic, mr.roughness});
  const BsdfFrame frame{s.ns, s.ng, s.frontFace};
  const Vec3 wo = -ray.dir;
  std::string note;
  ts.currentRecord = recIndex;

  Color color = glow;  // an emitter that also reflects (glTF's model) adds its glow
  if (hasSmoothLobe(bsdf)) {
    CachedAnswer storage;
    const CachedAnswer* cached = lookupAt(ctx, s, storage, ts);
    // The indirect view traces the direct term too: its gather depends on it.
    const bool withDirect = terms & kTermDirect;
    ts.medium = medium;  // where this point's shadow rays start
    const Color direct = (terms & (kTermDirect | kTermGlobal))
                             ? directLight(ctx, s, bsdf, frame, wo, cached, ts, withDirect && recIndex >= 0 ? &note : nullptr)
                             : Color(0.0f);
    if (withDirect) color += direct;
    if (terms & kTermCaustic)  // caustics are sharp: always the direct gather
      color += photonTerm(ctx, MapKindTag<MapKind::Caustic>{}, s, bsdf, frame, wo, nullptr, throughput, ts);
    if (terms & kTermGlobal) {
      // No light arrives directly: the global estimate is all the pixel has (umbra_gather.h).
      const bool unlit = !(maxComponent(direct) > 0.0f);
      color += photonTerm(ctx, MapKindTag<MapKind::Global>{}, s, bsdf, frame, wo, cached, throughput, ts, unlit);
    }
  }

  const RenderSettings& rs = ctx.scene.render;
  auto follow = [&](const Vec3& dir, const Color& w, RayKind k, uint8_t rayTerms) {
    Color next = throughput * w;
    if (!(k == RayKind::Reflection ? ctx.choices.reflection : ctx.choices.refraction)) return;  // the plan skips it
    if (maxComponent(next) <= rs.minWeight || ts.raysLeft <= 0) return;
    Ray r{spawnOrigin(s, dir), dir};
    const int beyond = ctx.scene.hasMedia() ? ctx.tracer.mediumBeyond(hit, s, dir, medium) : kNoMedium;
    color += w * tracePhysical(ctx, r, depth + 1, next, k, rayTerms, recIndex, ts, beyond);
  };
  if (depth < rs.maxDepth && (bsdfFlags(bsdf) & kBsdfNarrow)) {
    // One sampled ray of the narrow lobe carries its indirect light; the lights it
    // would see are already in the direct term, so it leaves emitters out.
    Rng rng(hashKey(ts.sampleKey ^ kNarrowStream, ts.shadingPoint));
    const float u1 = rng.uniform(), u2 = rng.uniform();
    const BsdfSample bs = sampleNarrowLobe(bsdf, frame, wo, u1, u2);
    if (bs.valid) follow(bs.wi, bs.weight, RayKind::Reflection, terms & ~kTermEmitters);
  }
  if (depth < rs.maxDepth && hasDeltaLobe(bsdf)) {
    if (bsdf.type == BsdfType::Dielectric) {
      const GlassSplit glass = splitAtGlass(ray, s, bsdf.ior, bsdf.tint);
      const float fr = glass.kr;
      const Color& kt = glass.kt;
      if (!glass.transmits && recIndex >= 0) note = "total internal reflection";
      // The stronger branch first: a tree that hits the ray budget loses the weaker.
      if (fr >= maxComponent(kt)) {
        follow(mirrorDirection(ray.dir, s), Color(fr), RayKind::Reflection, terms);
        if (glass.transmits) follow(glass.refracted, kt, RayKind::Refraction, terms);
      } else {
        follow(glass.refracted, kt, RayKind::Refraction, terms);
        follow(mirrorDirection(ray.dir, s), Color(fr), RayKind::Reflection, terms);
      }
    } else {
      follow(mirrorDirection(ray.dir, s), mirrorReflectance(bsdf, frame, wo), RayKind::Reflection, terms);
    }
  }
  if (recIndex >= 0) endRecord(ts, recIndex, hit, s, m, throughput * color, note);
  return color;
}

uint8_t physicalTerms(Aov aov) {
  switch (aov) {
    case Aov::Direct: return kTermDirect | kTermEmitters;
    case Aov::Caustic: return kTermCaustic;
    case Aov::Indirect: return kTermGlobal;
    default: return kTermAll;
  }
}

Color physicalSample(const ShadingContext& ctx, const Ray& ray, const Hit* hit, Aov aov, ThreadState& ts) {
  return tracePhysicalHit(ctx, ray, hit, 0, Color(1.0f), RayKind::Camera, physicalTerms(aov), -1, ts,
                          ctx.scene.cameraMedium);
}

void physicalTree(const ShadingContext& ctx, const Ray& ray, ThreadState& ts) {
  tracePhysical(ctx, ray, 0, Color(1.0f), RayKind::Camera, kTermAll, -1, ts, ctx.scene.cameraMedium);
}

// Direct light lands on smooth lobes only; a mirror or glass has none, unless a
// texture adds a diffuse albedo at the hit.
bool physicalShadesDirect(const Scene& scene, const Material& m) {
  return m.texture >= 0 || m.metalRoughTexture >= 0 || hasSmoothLobe(makeBsdf(m, BsdfFamily::Radiometric, scene.photons.sampling));
}

}  // namespace

const Integrator& physicalIntegrator() {
  static const Integrator kPhysical{shadingModelName(ShadingModel::Physical), physicalSample, physicalTree, physicalShadesDirect,
                                    GlassShadows::Block, true};
  return kPhysical;
}

}  // namespace penumbra
