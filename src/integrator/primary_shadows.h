// Shadow rays of a packet of camera hits, traced ahead as occlusion packets (one per
// light) and read back by the shading that would have cast them one at a time.
#pragma once
#include "integrator/shading.h"
#include <vector>

namespace penumbra {

// The lights (bit li, li < 32) whose shadow ray at a camera hit can be traced ahead:
// delta lights (one exact sample, no random numbers) that emit, with shadows on, a
// plain occlusion test (not the classic model's walk through glass) and no gate to
// consult (the gate decides whether a ray is cast at all). `direct`: the view adds
// direct light (classic beauty; physical beauty and direct); zero otherwise.
uint32_t packetShadowLights(const ShadingContext& ctx, bool direct);

// Reused buffers: one packet's worth of shadow rays and the hits they belong to.
struct PrimaryShadowScratch {
  std::vector<Ray> rays;
  std::vector<int> owner;
  std::vector<uint8_t> blocked;
};

// For n camera rays and their first hits (invalid: a miss), traces for every light
// of `lights` the shadow ray directFromLight would cast at that hit (shading point 1
// of its sample), as packets. Bit li of known[i] says hit i's answer for light li is
// in bit li of blocked[i]; hits that cannot cast one stay unknown and are answered by
// a single ray if shading asks after all, so the image never depends on this.
void tracePrimaryShadows(const ShadingContext& ctx, uint32_t lights, const Ray* rays,
                         const Hit* hits, int n, uint32_t* known, uint32_t* blocked,
                         PrimaryShadowScratch& scratch);

}  // namespace penumbra
