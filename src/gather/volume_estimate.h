// The volume photon map's estimate along a camera ray: the in-scattered radiance its
// photons send back over one medium segment (a beam radiance estimate, Jarosz,
// Zwicker & Jensen 2008), attenuated back to the segment's start.
#pragma once
#include "core/map_kind.h"
#include "core/media/medium.h"
#include "gather/photon_map_for.h"

namespace penumbra {

struct GatherScratch;
using VolumePhotonMap = PhotonMapFor<PhotonOf<MapKind::Volume>>;

// A ray's stretch [tMin, tMax] inside one medium.
struct VolumeQuery {
  Vec3 origin{0.0f};
  Vec3 dir{0.0f, 0.0f, 1.0f};  // unit, away from the camera
  float tMin = 0.0f, tMax = 0.0f;
};

struct VolumeEstimate {
  Color value{0.0f};   // radiance towards the ray's origin, times the transmittance from tMin
  uint32_t found = 0;  // photons that contributed
};

// radius: the beam's radius (0: the map's radius for k photons, as its build chose).
VolumeEstimate volumeRadiance(const VolumePhotonMap& map, const VolumeQuery& q, const Medium& medium, int k,
                              float radius, GatherScratch& scratch);

}  // namespace penumbra
