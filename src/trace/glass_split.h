// What a ray does at a glass surface, in both models: the Fresnel reflectance, the
// refracted direction if there is one, and the transmitted weight (tinted entering).
#pragma once
#include "core/optics.h"
#include "geometry/ray.h"
#include "geometry/trace_scene.h"

namespace penumbra {

struct GlassSplit {
  float kr = 1.0f;       // reflected share; 1 under total internal reflection
  Color kt{0.0f};        // transmitted weight
  Vec3 refracted{0.0f};  // valid when transmits
  bool transmits = false;
};

// Entering or leaving is decided by which side was hit, never by a flag carried
// along the path, so a ray that starts inside glass still exits.
inline GlassSplit splitAtGlass(const Ray& ray, const SurfaceRecord& s, float ior, const Color& tint) {
  GlassSplit g;
  const float etaI = s.frontFace ? 1.0f : ior;
  const float etaT = s.frontFace ? ior : 1.0f;
  g.kr = fresnelDielectric(glm::dot(s.ns, -ray.dir), etaI, etaT);
  g.transmits = refract(ray.dir, s.ns, etaI / etaT, g.refracted) && g.kr < 1.0f;
  if (!g.transmits) g.kr = 1.0f;
  g.kt = (1.0f - g.kr) * (s.frontFace ? tint : Color(1.0f));
  return g;
}

}  // namespace penumbra
