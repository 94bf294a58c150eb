// Mesh lights: the triangles of an emissive mesh as one Lambertian area light,
// sampled uniformly by area over all its triangles (MeshLight, core/lights/mesh_light.h,
// answers for it); the Lambert polygon formula here also serves the quad light.
#pragma once
#include "core/light_sample.h"
#include <vector>

namespace penumbra {

// A mesh light of radiance `radiance` (W/(sr m^2)) over `triangles` (world space, 3
// corners each, emitting on the side of (b - a) x (c - a)); triangles whose float area
// is 0 are left out. `material` is the emitting material's index. With `map`, the
// radiance is times its texel at `uvs` (3 per triangle) and triangles are drawn by
// area x luminance (core/emission_map.h).
struct EmissionMap;
Light makeMeshLight(const std::vector<Vec3>& triangles, const Color& radiance, int material,
                    const std::vector<Vec2>& uvs = {}, const EmissionMap* map = nullptr);

// Total area of a mesh light's triangles (its emitting area, per side).
inline float meshLightArea(const Light& light) {
  return light.areaCdf.empty() ? 0.0f : light.areaCdf.back();
}

// Its power over pi L: the area per side (the area x mean texel luminance when
// textured), twice over for a two-sided light.
float meshLightPowerFactor(const Light& light);

// MeshLight::irradiance's closed form runs up to this many triangles.
inline constexpr size_t kMeshClosedFormTriangles = 64;


// Lambert's formula for the polygon poly[0..m) (corners relative to the receiving
// point, m <= 4), clipped to the half-spaces above n and ng: the integral of
// cos(theta) over the solid angle it subtends above both, per unit radiance.
float clippedPolygonFactor(const Vec3* corners, int m, const Vec3& n, const Vec3& ng);

}  // namespace penumbra
