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

// Perturbs s.ns by the material's normal map: n' = normalize(T x scale + B y scale +
// N z) with (x, y, z) = 2 texel - 1 read as data, T the record's tangent made
// orthogonal to N, B = cross(N, T) x handedness, N the shading normal on the
// surface's outside. n' is turned back to the side the ray came from and kept on
// the geometric normal's side (as pbrt does). A record without a tangent is left as
// it is; a perturbed normal facing away from the viewer falls back to ng, as an
// interpolated one does (meshSurface). Needs normalMapFields(m) in the record.
void applyNormalMap(const Material& m, const TextureLookup& textures, float footprint, const Vec3& rayDir,
                    SurfaceRecord& s);

}  // namespace penumbra
