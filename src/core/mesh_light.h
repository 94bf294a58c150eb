// Mesh lights: the triangles of an emissive mesh as one Lambertian area light,
// sampled uniformly by area over all its triangles. Called from light_sample.cpp's
// dispatch; the Lambert polygon formula here also serves the quad light.
#pragma once
#include "core/light_sample.h"
#include <vector>

namespace penumbra {

// A mesh light of uniform radiance `radiance` (W/(sr m^2)) over `triangles` (world
// space, 3 corners each, emitting on the side of (b - a) x (c - a)); triangles whose
// float area is 0 are left out. `material` is the emitting material's index.
Light makeMeshLight(const std::vector<Vec3>& triangles, const Color& radiance, int material);

// Total area of a mesh light's triangles.
inline float meshLightArea(const Light& light) {
  return light.areaCdf.empty() ? 0.0f : light.areaCdf.back();
}

// One sample uniform by area (pdf_A = 1 / A): the incidence L cos_l A / d^2, invalid
// behind the sampled triangle's emitting side.
LightIncidence sampleMeshLight(const LightSampler& s, float u1, float u2);

// Closed-form unoccluded irradiance: Lambert's formula per triangle facing p, each
// clipped to the hemispheres of n and ng. False above kMeshClosedFormTriangles
// triangles (sample instead: the cost would grow with the mesh).
inline constexpr size_t kMeshClosedFormTriangles = 64;
bool meshLightIrradiance(const LightSampler& s, const Vec3& n, const Vec3& ng, Color& E);

// A photon from a uniform point (triangle by area from u1, position from u1's
// remainder and u2) in a cosine-weighted direction about that triangle's normal.
PhotonRay meshLightPhoton(const Light& light, float u1, float u2, float u3, float u4);

// Lambert's formula for the polygon poly[0..m) (corners relative to the receiving
// point, m <= 4), clipped to the half-spaces above n and ng: the integral of
// cos(theta) over the solid angle it subtends above both, per unit radiance.
float clippedPolygonFactor(const Vec3* corners, int m, const Vec3& n, const Vec3& ng);

}  // namespace penumbra
