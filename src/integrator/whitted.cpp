// Whitted recursion: local Phong lighting plus mirror and Fresnel-weighted
// refraction rays. Photon maps enter only through light_visibility.
#include "integrator/shading.h"
#include "core/optics.h"
#include "integrator/light_visibility.h"
#include "integrator/texture_lookup.h"

namespace penumbra {
namespace {

const char* kindName(RayKind k) {
  switch (k) {
    case RayKind::Camera: return "camera";
    case RayKind::Reflection: return "reflection";
    case RayKind::Refraction: return "refraction";
  }
  return "?";
}

void countRay(RayKind k, RayCounts& c) {
  if (k == RayKind::Camera) ++c.camera;
  else if (k == RayKind::Reflection) ++c.reflection;
  else ++c.refraction;
}

// Phong: ambient (or the indirect estimate) plus, per visible light, diffuse
// k_d (N.L) and specular k_s (R.V)^n. Point lights fall off with 1/d^2.
Color localShading(const ShadingContext& ctx, const SurfaceRecord& s, const Material& m,
                   const Vec3& toEye, const Color& texel, ThreadState& ts, RayRecord* rec) {
  Color lit = ambientTerm(ctx, s, m, ts);
  const auto& lights = ctx.scene.lights;
  for (uint32_t li = 0; li < lights.size(); ++li) {
    const Light& light = lights[li];
    if (maxComponent(light.radiance()) <= 0.0f) continue;  // nothing to add: skip the shadow test
    Vec3 toLight;
    float distance = kInf, falloff = 1.0f;
    if (light.type == LightType::Point) {
      Vec3 d = light.position - s.position;
      float d2 = glm::dot(d, d);
      if (!(d2 > 0.0f)) continue;
      distance = std::sqrt(d2);
      toLight = d / distance;
      falloff = 1.0f / d2;
    } else {
      toLight = -light.direction;
    }
    // A light behind the geometric surface cannot reach it: no shadow test needed.
    if (glm::dot(s.ng, toLight) <= 0.0f) continue;
    float nDotL = glm::dot(s.ns, toLight);
    if (nDotL <= 0.0f) continue;
    std::string note;
    Color vis = lightVisibility(ctx, s, li, toLight, distance, ts, rec ? &note : nullptr);
    if (rec && !note.empty()) rec->note += (rec->note.empty() ? "" : "; ") + note;
    if (maxComponent(vis) <= 0.0f) continue;
    Color c = m.diffuse * nDotL;
    if (m.shininess > 0.0f && maxComponent(m.specular) > 0.0f) {
      float rDotV = glm::dot(reflect(-toLight, s.ns), toEye);
      if (rDotV > 0.0f) c += m.specular * std::pow(rDotV, m.shininess);
    }
    lit += vis * light.radiance() * falloff * c;
  }
  if (m.texture >= 0) lit = m.textureBlend == TextureBlend::Multiply ? lit * texel : lit + texel;
  return lit;
}

// A shading normal can bend the mirror direction under the surface; fall back
// to the geometric normal rather than reflect into the object.
Vec3 mirrorDirection(const Vec3& dir, const SurfaceRecord& s) {
  Vec3 r = reflect(dir, s.ns);
  return glm::dot(r, s.ng) > 0.0f ? r : reflect(dir, s.ng);
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
  countRay(kind, ts.counts);
  --ts.raysLeft;
  int recIndex = -1;
  if (ts.recorder) {
    RayRecord r;
    r.kind = kindName(kind);
    r.parent = parentRecord;
    r.depth = depth;
    r.origin = ray.origin;
    r.dir = ray.dir;
    r.weight = weight;
    recIndex = static_cast<int>(ts.recorder->size());
    ts.recorder->push_back(r);
  }
  auto finish = [&](const Color& c, auto&& fill) {
    if (recIndex >= 0) {
      RayRecord& r = (*ts.recorder)[recIndex];
      fill(r);
      r.contribution = weight * c;
    }
    return c;
  };

  Hit hit;
  if (!ctx.tracer.intersect(ray, hit)) {
    return finish(ctx.scene.render.background, [](RayRecord&) {});
  }
  const Material& m = ctx.scene.materials[ctx.tracer.materialOf(hit)];
  SurfaceRecord s = ctx.tracer.surface(ray, hit, m.texture >= 0 ? kSurfaceAll : kSurfaceShadingNormal);
  Vec3 toEye = -ray.dir;
  float footprint = cone + hit.t * ctx.pixelSpread;

  Color texel(1.0f);
  if (m.texture >= 0 && ctx.textures) texel = ctx.textures->lookup(m.texture, s, footprint);

  // Local shading records its gate notes into this ray's record; fetch the
  // pointer after children may have grown the vector, never hold it across.
  RayRecord scratchRec;
  ts.currentRecord = recIndex;
  Color color = localShading(ctx, s, m, toEye, texel, ts, recIndex >= 0 ? &scratchRec : nullptr);

  const RenderSettings& rs = ctx.scene.render;
  bool deeper = depth < rs.maxDepth;
  std::string note;
  if (deeper && m.transparent) {
    // Entering or leaving is decided by which side was hit, never by a flag
    // carried along the path, so a ray that starts inside glass still exits.
    float etaI = s.frontFace ? 1.0f : m.ior;
    float etaT = s.frontFace ? m.ior : 1.0f;
    float cosI = glm::dot(s.ns, toEye);
    float kr = fresnelDielectric(cosI, etaI, etaT);
    Vec3 tdir;
    bool transmits = refract(ray.dir, s.ns, etaI / etaT, tdir) && kr < 1.0f;
    if (!transmits) { kr = 1.0f; note = "total internal reflection"; }
    Color kt = (1.0f - kr) * (s.frontFace ? m.tint : Color(1.0f));
    Color reflW = weight * kr, transW = weight * kt;
    // Both branches of every glass hit would double the tree per level; the
    // stronger one goes first so a tree that hits the per-sample ray budget
    // loses its weakest light.
    auto reflectBranch = [&] {
      if (maxComponent(reflW) <= rs.minWeight || ts.raysLeft <= 0) return;
      Ray r{s.position, mirrorDirection(ray.dir, s)};
      r.origin = offsetRayOrigin(s.position, s.ng, r.dir);
      color += kr * traceRay(ctx, r, depth + 1, reflW, footprint, RayKind::Reflection, recIndex, ts);
    };
    auto refractBranch = [&] {
      if (!transmits || maxComponent(transW) <= rs.minWeight || ts.raysLeft <= 0) return;
      Ray r{offsetRayOrigin(s.position, s.ng, tdir), tdir};
      color += kt * traceRay(ctx, r, depth + 1, transW, footprint, RayKind::Refraction, recIndex, ts);
    };
    if (maxComponent(reflW) >= maxComponent(transW)) {
      reflectBranch();
      refractBranch();
    } else {
      refractBranch();
      reflectBranch();
    }
  } else if (deeper && m.kr > 0.0f && maxComponent(weight) * m.kr > rs.minWeight && ts.raysLeft > 0) {
    Vec3 rdir = mirrorDirection(ray.dir, s);
    Ray r{offsetRayOrigin(s.position, s.ng, rdir), rdir};
    color += m.kr * traceRay(ctx, r, depth + 1, weight * m.kr, footprint, RayKind::Reflection, recIndex, ts);
  }

  return finish(color, [&](RayRecord& r) {
    r.hit = true;
    r.t = hit.t;
    r.position = s.position;
    r.material = m.name;
    r.entering = s.frontFace;
    r.note = scratchRec.note;
    if (!note.empty()) r.note += (r.note.empty() ? "" : "; ") + note;
  });
}

}  // namespace penumbra
