// Tangent-space normal maps: the shading normal a material's map gives at a hit, in
// both shading models, before any BSDF is evaluated.
#pragma once
#include "core/scene.h"
#include "geometry/trace_scene.h"

namespace penumbra {

class TextureLookup;

// Perturbs the record's shading normal by the material's normal map, read as data in
// tangent space: the texel maps to a direction in the frame of the hit's tangent
// (TraceScene::tangent, made orthogonal to the shading normal), its bitangent (with
// the tangent's handedness) and the shading normal, the tangent-plane part scaled by
// normal_scale. The result faces the side the ray came from and stays on the
// geometric normal's side (as pbrt does); a hit without a tangent is left as it is,
// and a normal facing away from the viewer falls back to ng, as an interpolated one
// does (meshSurface).
// Needs kSurfaceAll in the record; does nothing for a material without a map.
void applyNormalMap(const Material& m, const TextureLookup& textures, const TraceScene& tracer, const Hit& hit,
                    float footprint, const Vec3& rayDir, SurfaceRecord& s);

}  // namespace penumbra
