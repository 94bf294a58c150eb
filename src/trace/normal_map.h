// Tangent-space normal maps: the shading normal a material's map gives at a hit, in
// both shading models, before any BSDF is evaluated.
#pragma once
#include "core/scene.h"
#include "geometry/trace_scene.h"

namespace penumbra {

class TextureLookup;

// The record fields a normal-mapped material needs besides the rest (0 without a map).
inline uint8_t normalMapFields(const Material& m) {
  return m.normalTexture >= 0 ? uint8_t(kSurfaceAll | kSurfaceTangent) : uint8_t(0);
}

// Perturbs s.ns by the material's normal map, read as data in tangent space: the
// texel maps to a direction in the frame of the record's tangent (made orthogonal
// to the shading normal), its bitangent (with the tangent's handedness) and the
// shading normal, the tangent-plane part scaled by normal_scale. The result faces
// the side the ray came from and stays on the geometric normal's side (as pbrt
// does); a record without a tangent is left as it is, and a normal facing away from
// the viewer falls back to ng, as an interpolated one does (meshSurface). Needs
// normalMapFields(m) in the record.
void applyNormalMap(const Material& m, const TextureLookup& textures, float footprint, const Vec3& rayDir,
                    SurfaceRecord& s);

}  // namespace penumbra
