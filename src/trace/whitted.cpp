// Whitted recursion: local Phong lighting plus mirror and Fresnel-weighted
// refraction rays. Photon maps enter only through light_visibility.
#include "trace/shading.h"
#include "core/bsdf.h"
#include "core/light_sample.h"
#include "core/optics.h"
#include "trace/environment_light.h"
#include "trace/glass_split.h"
#include "trace/light_visibility.h"
#include "trace/normal_map.h"
#include "trace/texture_lookup.h"

namespace penumbra {
namespace {

// Phong through the BSDF and light interfaces: ambient (or the indirect estimate)
// plus, per visible light, the classic BSDF (k_d N.L + k_s (R.V)^n) times the
// light's incident term (I / d^2 for point lights). The vertex colour `tint` is in
// the BSDF's base already; the ambient term, the base's too, takes it here.
Color localShading(const ShadingContext& ctx, const SurfaceRecord& s, const Material& m, const Bsdf& bsdf,
                   const Vec3& toEye, const Color& texel, const Color& tint, ThreadState& ts, RayRecord* rec) {
  CachedAnswer storage;
  const CachedAnswer* cached = lookupAt(ctx, s, storage, ts);
  Color lit = ambientTerm(ctx, s, m, cached, ts) * tint;
  const BsdfFrame frame{s.ns, s.ng, s.frontFace};
  const auto& lights = ctx.scene.lights;
  ++ts.shadingPoint;
  for (uint32_t li = 0; li < lights.size(); ++li) {
    if (maxComponent(lights[li].radiance()) <= 0.0f) continue;  // nothing to add: skip the shadow test
    std::string note;
    if (lightTraits(lights[li]).direct == DirectSampling::EnvironmentMis) {
      lit += directFromEnvironment(ctx, s, li, bsdf, frame, toEye, ts, rec ? &note : nullptr);
    } else {
      lit += directFromLight(
          ctx, s, li, cached, ts, rec ? &note : nullptr, bsdf, frame, toEye,
          [](const Color& t, const Color& f, const LightIncidence& in) { return t * in.radiance * f; });
    }
    if (rec && !note.empty()) rec->note += (rec->note.empty() ? "" : "; ") + note;
  }
  if (m.texture >= 0) lit = m.textureBlend == TextureBlend::Multiply ? lit * texel : lit + texel;
  return lit;
}

}  // namespace

bool sceneHasGlass(const Scene& scene) {
  for (const Material& m : scene.materials) {
    if (m.transparent) return true;
  }
  return false;
}

Color traceRay(const ShadingContext& ctx, const Ray& ray, int depth, const Color& weight,
               float cone, RayKind kind, int parentRecord, ThreadState& ts) {
  Hit hit;
  const bool found = ctx.tracer.intersect(ray, hit);
  return traceRayHit(ctx, ray, found ? &hit : nullptr, depth, weight, cone, kind, parentRecord, ts);
}

Color traceRayHit(const ShadingContext& ctx, const Ray& ray, const Hit* found, int depth,
                  const Color& weight, float cone, RayKind kind, int parentRecord, ThreadState& ts) {
  countRay(kind, ts.counts);
  --ts.raysLeft;
  int recIndex = ts.recorder ? beginRecord(ts, kind, ray, depth, weight, parentRecord) : -1;
  auto finish = [&](const Color& c, auto&& fill) {
    if (recIndex >= 0) {
      RayRecord& r = (*ts.recorder)[recIndex];
      fill(r);
      r.contribution = weight * c;
    }
    return c;
  };

  if (!found) return finish(missRadiance(ctx.scene, ray.dir, kind), [](RayRecord&) {});
  const Hit& hit = *found;
  const Material& m = ctx.scene.materials[ctx.tracer.materialOf(hit)];
  const bool textured = readsUv(m);
  SurfaceRecord s = ctx.tracer.surface(ray, hit, textured ? kSurfaceAll : kSurfaceShadingNormal);
  auto recordHit = [&](RayRecord& r) {
    r.hit = true;
    r.t = hit.t;
    r.position = s.position;
    r.material = m.name;
    r.entering = s.frontFace;
  };
  Vec3 toEye = -ray.dir;
  float footprint = cone + hit.t * ctx.pixelSpread;
  // Whitted rays never sample a light's surface, so every ray sees its glow.
  const Color glow = emitterGlow(ctx, m, s, footprint, false);
  if (maxComponent(m.emission) > 0.0f && !m.emitterShades) return finish(glow, recordHit);  // a light's surface

  const Vec3 interpolated = s.ns;
  if (ctx.textures) applyNormalMap(m, *ctx.textures, ctx.tracer, hit, footprint, ray.dir, s);
  Color texel(1.0f);
  if (m.texture >= 0 && ctx.textures) texel = ctx.textures->lookup(m.texture, s, footprint, m.uvTransform());
  const Color tint(ctx.tracer.vertexColor(hit));
  Bsdf bsdf = makeBsdf(m, BsdfFamily::Phong, ctx.scene.photons.sampling, tint);
  MetalRough mr{m.metallic, m.roughness};
  if (m.metalRoughTexture >= 0 && ctx.textures) {
    mr = metalRoughAt(m, *ctx.textures, s, footprint);
    setMetalRough(bsdf, BsdfFamily::Phong, m.diffuse * tint, mr.metallic, mr.roughness);
  }
  if (recIndex >= 0) {
    // The classic model applies the texture to the lit colour; the base is the same product.
    const Color base = m.texture < 0 ? m.diffuse * tint
                       : m.textureBlend == TextureBlend::Multiply ? m.diffuse * tint * texel
                                                                   : m.diffuse * tint + texel;
    recordSurface(ts, recIndex, s, interpolated, m, {base, mr.metallic, mr.roughness});
  }

  // Local shading records its gate notes into this ray's record; fetch the
  // pointer after children may have grown the vector, never hold it across.
  RayRecord scratchRec;
  ts.currentRecord = recIndex;
  Color color = glow + localShading(ctx, s, m, bsdf, toEye, texel, tint, ts, recIndex >= 0 ? &scratchRec : nullptr);

  const RenderSettings& rs = ctx.scene.render;
  bool deeper = depth < rs.maxDepth;
  std::string note;
  if (deeper && m.transparent) {
    const GlassSplit glass = splitAtGlass(ray, s, m.ior, m.tint);
    const float kr = glass.kr;
    const Color kt = glass.kt;
    const bool transmits = glass.transmits;
    const Vec3 tdir = glass.refracted;
    if (!transmits) note = "total internal reflection";
    Color reflW = weight * kr, transW = weight * kt;
    // Both branches of every glass hit would double the tree per level; the
    // stronger one goes first so a tree that hits the per-sample ray budget
    // loses its weakest light.
    auto reflectBranch = [&] {
      if (!ctx.choices.reflection || maxComponent(reflW) <= rs.minWeight || ts.raysLeft <= 0) return;
      Ray r{s.position, mirrorDirection(ray.dir, s)};
      r.origin = spawnOrigin(s, r.dir);
      color += kr * traceRay(ctx, r, depth + 1, reflW, footprint, RayKind::Reflection, recIndex, ts);
    };
    auto refractBranch = [&] {
      if (!ctx.choices.refraction || !transmits || maxComponent(transW) <= rs.minWeight || ts.raysLeft <= 0) return;
      Ray r{spawnOrigin(s, tdir), tdir};
      color += kt * traceRay(ctx, r, depth + 1, transW, footprint, RayKind::Refraction, recIndex, ts);
    };
    if (maxComponent(reflW) >= maxComponent(transW)) {
      reflectBranch();
      refractBranch();
    } else {
      refractBranch();
      reflectBranch();
    }
  } else if (deeper && ctx.choices.reflection && bsdf.kr > 0.0f && maxComponent(weight) * bsdf.kr > rs.minWeight &&
             ts.raysLeft > 0) {
    Vec3 rdir = mirrorDirection(ray.dir, s);
    Ray r{spawnOrigin(s, rdir), rdir};
    color += bsdf.kr * traceRay(ctx, r, depth + 1, weight * bsdf.kr, footprint, RayKind::Reflection, recIndex, ts);
  }

  return finish(color, [&](RayRecord& r) {
    recordHit(r);
    r.note = scratchRec.note;
    if (!note.empty()) r.note += (r.note.empty() ? "" : "; ") + note;
  });
}

namespace {

// Beauty is the whole recursion; the indirect view is the ambient term alone (the
// indirect map's estimate, or render.ambient without one).
Color whittedSample(const ShadingContext& ctx, const Ray& ray, const Hit* hit, Aov aov, ThreadState& ts) {
  if (aov == Aov::Beauty) return traceRayHit(ctx, ray, hit, 0, Color(1.0f), 0.0f, RayKind::Camera, -1, ts);
  ++ts.counts.camera;
  if (!hit) return Color(0.0f);
  const SurfaceRecord s = ctx.tracer.surface(ray, *hit, kSurfaceShadingNormal);
  CachedAnswer storage;
  return ambientTerm(ctx, s, ctx.scene.materials[s.material], lookupAt(ctx, s, storage, ts), ts) *
         Color(ctx.tracer.vertexColor(*hit));
}

void whittedTree(const ShadingContext& ctx, const Ray& ray, ThreadState& ts) {
  traceRay(ctx, ray, 0, Color(1.0f), 0.0f, RayKind::Camera, -1, ts);
}

// Phong lights every surface that is not itself a light.
bool whittedShadesDirect(const Scene&, const Material&) { return true; }

}  // namespace

const Integrator& whittedIntegrator() {
  static const Integrator kWhitted{shadingModelName(ShadingModel::Classic), whittedSample, whittedTree, whittedShadesDirect, GlassShadows::Tint,
                                   false};
  return kWhitted;
}

}  // namespace penumbra
