// Caustic photons aimed at the specular objects' bounding spheres (Jensen's projection
// maps): directions (point and area lights) or disc points (directional lights) drawn
// from a mixture of one cone or disc per target, each photon's power divided by the
// mixture's density, so overlapping targets count once and the estimate stays unbiased.
#pragma once
#include "core/light_sample.h"
#include "core/rng.h"
#include <vector>

namespace penumbra {

// Point, directional, quad, sphere and mesh lights aim. A spot emits unaimed (its cone
// would cut the aim), and so does an environment.
bool aimsCausticPhotons(const Light& light);

// One light's aim. A point or directional light's cones (discs) are fixed; an area
// light's are drawn anew from each photon's start on its surface.
struct CausticAim {
  const std::vector<SceneSphere>* targets = nullptr;
  std::vector<float> measure;  // per target: solid angle (point) or disc area (directional)
  float total = 0.0f;
  // The share of the light's power that heads for a target: its budget weight.
  double share = 0.0;
};

// `key` seeds the few photons that measure an area light's share.
CausticAim aimAt(const Light& light, const std::vector<SceneSphere>& targets, const SceneSphere& bounds,
                 uint64_t key);

// One aimed photon into `r`. Returns the factor on the light's unaimed photon power
// (the unaimed density over the mixture's), 0 when it heads for no target. `scratch`
// holds an area light's per-target cones (reused, so a batch allocates once).
float sampleAimed(const Light& light, const SceneSphere& bounds, const CausticAim& aim, Rng& rng,
                  PhotonRay& r, std::vector<float>& scratch);

}  // namespace penumbra
