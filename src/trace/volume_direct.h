// Light scattered once in a medium into a ray, by light sampling: equiangular and
// distance samples under the balance heuristic (Kulla & Fajardo 2012).
#pragma once
#include "core/media/homogeneous.h"
#include "core/rng.h"
#include "trace/shading.h"

namespace penumbra {

// Distances along one stretch [a, b] (b may be infinite) by free flight at the medium's
// mean extinction (its majorant in a grid), truncated to the stretch
// (core/media/homogeneous.h), in the ray's own parameter.
struct FreeFlight {
  float a = 0.0f, length = 0.0f, s = 0.0f;
  FreeFlight(const Medium& m, float from, float to) : a(from), length(to - from), s(rateOf(m)) {}
  static float rateOf(const Medium& m);
  DistanceSample sample(float u) const {
    DistanceSample d = sampleTruncatedFreeFlight(s, length, u);
    d.t += a;
    return d;
  }
  float pdf(float t) const { return float(truncatedFreeFlightPdf(s, length, t - a)); }
};

// The radiance that medium `medium` scatters once from every light into `ray` over its
// stretch [a, b] (b infinite on a miss), attenuated back to a but not before it. Per
// light, render.volume_samples times (stratified): point, spot and area lights take an
// equiangular sample about the light's position (an area light: a point drawn on it)
// and a distance sample, each lit by a light sample and a shadow ray that carries the
// transmittance; directional and environment lights the distance sample alone.
Color volumeDirect(const ShadingContext& ctx, const Ray& ray, float a, float b, int medium, Rng& rng,
                   ThreadState& ts);

}  // namespace penumbra
