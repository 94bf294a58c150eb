// Transmittance along shadow segments in scenes with media: Beer–Lambert through each
// medium a segment crosses, the medium changing only at invisible boundaries.
#pragma once
#include "trace/shading.h"

namespace penumbra {

struct Medium;

// A grid medium's [a, b] clipped to its density box (zero density outside, so nothing
// is lost): false when the two do not meet. Tracking then never steps across the empty
// world, nor towards an infinite end. Homogeneous media keep [a, b].
bool gridSpan(const Medium& m, const Ray& ray, float& a, float& b);

// Transmittance over [a, b] of `ray` inside one medium, b = infinity included (0 where
// sigmaT > 0, else 1): closed form when homogeneous, else ratio tracking on a stream
// of this sample's (ts.mediumDraws).
Color stretchTransmittance(const Medium& m, const Ray& ray, float a, float b, ThreadState& ts);

// Transmittance over [ray.tMin, tEnd] of a segment that crosses no surface, starting
// in `medium`: closed form in a homogeneous medium when the scene has no invisible
// boundary, else a walk over the boundaries (tracking in grids). Counts a
// transmittance ray when the segment spends any length in a medium.
Color segmentTransmittance(const ShadingContext& ctx, const Ray& ray, float tEnd, int medium, ThreadState& ts);

// A shadow ray to light `li` from a point in `medium` (physical model, where glass
// blocks): 0 when a surface blocks it (the light's own surface meeting it first counts
// as arrival for the lights whose ShadowTest says so), else the media's transmittance
// up to the light's point, `margin` past ray.tMax. Without media: a plain 0 or 1.
Color lightTransmittance(const ShadingContext& ctx, const Ray& ray, float margin, uint32_t li, int medium,
                         ThreadState& ts);

}  // namespace penumbra
