// The environment at a shading point and beyond the scene: direct light by light
// samples and BSDF samples under the power heuristic (shadow rays only: the gate has
// no photons of an environment), and the radiance a ray that leaves the scene sees.
#pragma once
#include "core/bsdf.h"
#include "trace/shading.h"
#include <string>

namespace penumbra {

// Direct light from environment light `li` at s: render.light_samples light samples
// (core/lights/environment_map.h: a map by luminance, a constant sky cosine-weighted about the
// shading normal) and, where the BSDF draws its own directions (physical Opaque and
// MetalRough: pdfBsdf > 0), as many BSDF samples that leave the scene; the two are
// weighted by the power heuristic, so neither a small bright patch nor a tight glossy
// lobe is left to the other's noise. The classic Phong BSDF has no sampling pdf: its
// light samples stand alone (weight 1). Each sample casts a shadow ray (glass tints
// it in classic, blocks it in physical, as for every light); the gate is never asked:
// an environment emits no shadow photons (its light has no position to vote about).
Color directFromEnvironment(const ShadingContext& ctx, const SurfaceRecord& s, uint32_t li, const Bsdf& bsdf,
                            const BsdfFrame& frame, const Vec3& wo, ThreadState& ts, std::string* note);

// Whether a ray of `kind` that leaves the scene sees the environment (a light) rather
// than a background colour: render.background without an environment, and for camera
// rays render.environmentBackground when it is set (the studio's grey behind a model).
bool missSeesEnvironment(const Scene& scene, RayKind kind);
// What that ray sees along unit `dir`: the environment's radiance or the background.
Color missRadiance(const Scene& scene, const Vec3& dir, RayKind kind);

}  // namespace penumbra
