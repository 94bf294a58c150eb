// Tangent-space normal mapping: the map's texel, read as data, turned into a
// shading normal in the hit's tangent frame (glTF 2.0's normalTexture rule).
#include "trace/normal_map.h"
#include "trace/texture_lookup.h"

namespace penumbra {

void applyNormalMap(const Material& m, const TextureLookup& textures, const TraceScene& tracer, const Hit& hit,
                    float footprint, const Vec3& rayDir, SurfaceRecord& s) {
  if (m.normalTexture < 0) return;
  const glm::vec4 tangent = tracer.tangent(hit);
  if (tangent.w == 0.0f) return;
  const Color texel = textures.lookup(m.normalTexture, s, footprint, m.uvTransform());
  // glTF: normalize((2 texel - 1) * (scale, scale, 1)).
  const Vec3 local((2.0f * texel.r - 1.0f) * m.normalScale, (2.0f * texel.g - 1.0f) * m.normalScale,
                   2.0f * texel.b - 1.0f);
  // The frame on the outside of the surface, where the map's +z points: the record's
  // normals face the ray, so a back-face hit turns N around first.
  const Vec3 n = s.frontFace ? s.ns : -s.ns;
  Vec3 t = Vec3(tangent) - n * glm::dot(n, Vec3(tangent));
  const float tLen = glm::length(t);
  if (!(tLen > 1e-12f)) return;  // a tangent along the normal gives no frame
  t /= tLen;
  const Vec3 b = glm::cross(n, t) * tangent.w;
  Vec3 p = t * local.x + b * local.y + n * local.z;
  const float pLen = glm::length(p);
  if (!(pLen > 1e-12f) || !std::isfinite(pLen)) return;
  p /= pLen;
  if (!s.frontFace) p = -p;
  // pbrt's rule: the shading normal lies in the geometric normal's hemisphere.
  if (glm::dot(p, s.ng) < 0.0f) p = -p;
  s.ns = glm::dot(p, rayDir) > 0.0f ? s.ng : p;
}

}  // namespace penumbra
