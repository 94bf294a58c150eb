// How much of a light reaches a shading point: the photon-map ambiguity gate
// decides when a shadow ray is needed; shadow rays through glass are tinted.
#pragma once
#include "gather/lookup_cache.h"
#include "integrator/shading.h"

namespace penumbra {

// How much of a light reaches a point (1 = unoccluded), from the gate or a shadow
// ray. Classic: glass tints the ray; physical: glass blocks it like anything else
// (light through glass arrives as caustic photons).
// The gate's vote parameters for this scene (also what a lookup cache precomputes).
GateParams gateParamsFor(const Scene& scene);

// `cached` is the shading point's precomputed answer (null: ask the photon map).
using CachedAnswer = LookupCache::Answer;
Color lightVisibility(const ShadingContext& ctx, const SurfaceRecord& s, uint32_t lightIndex,
                      const Vec3& toLight, float distance, const CachedAnswer* cached,
                      ThreadState& ts, std::string* note);

// The precomputed answer at a shading point, or null without a lookup cache.
const CachedAnswer* lookupAt(const ShadingContext& ctx, const SurfaceRecord& s,
                             CachedAnswer& storage, ThreadState& ts);

// The term that replaces ambient light: the indirect photon map's estimate, or
// the material's ambient colour times the global ambient when there is no map.
Color ambientTerm(const ShadingContext& ctx, const SurfaceRecord& s, const Material& m,
                  const CachedAnswer* cached, ThreadState& ts);

}  // namespace penumbra
