// Helpers both integrators share: counting rays by kind, recording the ray tree
// of one pixel (--trace-pixel, never on the render's hot path), mirror directions and
// the glow of emitting surfaces.
#include "core/optics.h"
#include "trace/shading.h"
#include "trace/texture_lookup.h"

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
}  // namespace

void countRay(RayKind k, RayCounts& c) {
  if (k == RayKind::Camera) ++c.camera;
  else if (k == RayKind::Reflection) ++c.reflection;
  else ++c.refraction;
}

int beginRecord(ThreadState& ts, RayKind kind, const Ray& ray, int depth, const Color& weight,
                int parent) {
  RayRecord r;
  r.kind = kindName(kind);
  r.parent = parent;
  r.depth = depth;
  r.origin = ray.origin;
  r.dir = ray.dir;
  r.weight = weight;
  ts.recorder->push_back(r);
  return static_cast<int>(ts.recorder->size()) - 1;
}

void endRecord(ThreadState& ts, int index, const Hit& hit, const SurfaceRecord& s,
               const Material& m, const Color& contribution, const std::string& note) {
  RayRecord& r = (*ts.recorder)[index];
  r.hit = true;
  r.t = hit.t;
  r.position = s.position;
  r.material = m.name;
  r.entering = s.frontFace;
  r.contribution = contribution;
  if (!note.empty()) r.note += (r.note.empty() ? "" : "; ") + note;
}

void recordSurface(ThreadState& ts, int index, const SurfaceRecord& s, const Vec3& interpolated, const Material& m,
                   const EvaluatedMaterial& evaluated) {
  RayRecord& r = (*ts.recorder)[size_t(index)];
  r.shaded = true;
  r.hasUv = readsUv(m);
  r.uv = s.uv;
  r.geometricNormal = s.ng;
  r.interpolatedNormal = interpolated;
  r.shadingNormal = s.ns;
  r.baseColor = evaluated.base;
  r.metalRough = m.metalRough;
  r.metallic = evaluated.metallic;
  r.roughness = evaluated.roughness;
}

// A shading normal can bend the mirror direction under the surface; fall back
// to the geometric normal rather than reflect into the object.
Vec3 mirrorDirection(const Vec3& dir, const SurfaceRecord& s) {
  Vec3 r = reflect(dir, s.ns);
  return glm::dot(r, s.ng) > 0.0f ? r : reflect(dir, s.ng);
}

Color emitterGlow(const ShadingContext& ctx, const Material& m, const SurfaceRecord& s, float footprint,
                  bool lightsSampled) {
  if (!(maxComponent(m.emission) > 0.0f) || (lightsSampled && m.light >= 0)) return Color(0.0f);
  if (!s.frontFace && !m.twoSidedEmission) return Color(0.0f);
  if (m.emissionTexture < 0 || !ctx.textures) return m.emission;
  return m.emission * ctx.textures->lookup(m.emissionTexture, s, footprint, m.uvTransform());
}

}  // namespace penumbra
