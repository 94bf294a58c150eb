// How much of a light reaches a shading point: the photon-map ambiguity gate
// decides when a shadow ray is needed; shadow rays through glass are tinted.
#pragma once
#include "integrator/shading.h"

namespace penumbra {

// Fraction (per channel) of light `lightIndex` arriving at `s` from direction
// `toLight` (unit) over `distance` (kInf for directional lights).
Color lightVisibility(const ShadingContext& ctx, const SurfaceRecord& s, uint32_t lightIndex,
                      const Vec3& toLight, float distance, ThreadState& ts, std::string* note);

// The term that replaces ambient light: the indirect photon map's estimate, or
// the material's ambient colour times the global ambient when there is no map.
Color ambientTerm(const ShadingContext& ctx, const SurfaceRecord& s, const Material& m,
                  ThreadState& ts);

}  // namespace penumbra
