// A ray's way through participating media up to its surface hit (or to infinity on a
// miss): the light the media add along it and the transmittance they leave for what lies beyond.
#pragma once
#include "trace/shading.h"

namespace penumbra {

struct MediumStretch {
  Color radiance{0.0f};       // added along the ray, attenuated back to its origin
  Color transmittance{1.0f};  // from the origin to tEnd: multiplies what lies beyond
  int medium = kNoMedium;     // the medium at tEnd (after any invisible boundaries)
};

// Walks `ray` from its origin in `medium` to tEnd, through invisible boundaries. Each
// stretch inside a medium adds, by the physical terms asked for (trace/physical.h):
// single scattering by light sampling (direct), the medium's emission (direct or
// emitters: no light sampling covers it), the volume photon map's beam estimate
// (global: multiple scattering and volume caustics). A stretch in vacuum costs nothing.
MediumStretch traceMediumStretch(const ShadingContext& ctx, const Ray& ray, float tEnd, int medium, uint8_t terms,
                                 ThreadState& ts);

}  // namespace penumbra
