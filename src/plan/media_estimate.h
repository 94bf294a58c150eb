// What participating media add to a render's cost, from the scene alone: the volume
// map's stores per photon and its photons' events, and the camera rays' work in a
// medium (light samples with their transmittance rays, tracking, the beam gather).
#pragma once
#include "core/scene.h"
#include <nlohmann/json_fwd.hpp>

namespace penumbra {

struct MediaCost {
  bool any = false;             // the scene has a medium (all else 0 without)
  double storesPerPhoton = 0.0; // volume map: scatter events stored per emitted photon (a bound)
  double photonEventNs = 0.0;   // per photon flight in a medium: free-flight, roulette, phase sample
  double cameraShare = 0.0;     // camera rays that cross a medium (1: the camera or the scene is in one)
  // One camera ray's medium work, in ns: light samples with their transmittance rays,
  // tracking steps in density grids, and the volume map's beam gather.
  double sampleNs = 0.0, trackingNs = 0.0, gatherNs = 0.0;
  double rayNs() const { return sampleNs + trackingNs + gatherNs; }
};

// `volumeStoredPerPass`: the volume map's photons a pass (0: no map, no gather priced).
MediaCost mediaCost(const Scene& scene, double volumeStoredPerPass);

// The estimate's "media" object (only a scene with a medium writes one).
nlohmann::json mediaCostJson(const MediaCost& m, double cameraSeconds, double photonSeconds);

}  // namespace penumbra
