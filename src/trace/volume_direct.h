// Light scattered once in a medium into a ray, by light sampling: equiangular and
// distance samples under the balance heuristic (Kulla & Fajardo 2012).
#pragma once
#include "core/rng.h"
#include "trace/shading.h"

namespace penumbra {

// Distances along one stretch [a, b] (b may be infinite) drawn with density
// s exp(-s (t - a)), truncated to the stretch: s is the medium's mean extinction (its
// majorant in a grid), the free-flight density of sampleCollision.
struct FreeFlight {
  float a = 0.0f, b = 0.0f, s = 0.0f, norm = 0.0f;  // norm: the mass inside [a, b]
  FreeFlight(float rate, float from, float to);
  bool valid() const { return s > 0.0f && norm > 0.0f; }
  float sample(float u) const;
  float pdf(float t) const;
};

// The radiance that medium `medium` scatters once from every light into `ray` over its
// stretch [a, b] (b infinite on a miss), attenuated back to a but not before it. Point,
// spot, quad, disk and sphere lights: one equiangular sample about the light's centre
// and one distance sample, each lit by a light sample and a shadow ray that carries the
// transmittance. Mesh, directional and environment lights: the distance sample alone.
Color volumeDirect(const ShadingContext& ctx, const Ray& ray, float a, float b, int medium, Rng& rng,
                   ThreadState& ts);

}  // namespace penumbra
