// The volume photon map's estimate along a camera ray: the in-scattered radiance its
// photons send back over one medium segment (a beam radiance estimate, Jarosz,
// Zwicker & Jensen 2008), attenuated back to the segment's start.
#pragma once
#include "core/map_kind.h"
#include "core/media/medium.h"
#include "gather/photon_map_for.h"
#include "gather/volume_map.h"

namespace penumbra {

struct GatherScratch;
static_assert(std::is_same_v<PhotonMapFor<PhotonOf<MapKind::Volume>>, VolumePhotonMap>);

// A ray's stretch [tMin, tMax] inside one medium.
struct VolumeQuery {
  Vec3 origin{0.0f};
  Vec3 dir{0.0f, 0.0f, 1.0f};  // unit, away from the camera
  float tMin = 0.0f, tMax = 0.0f;
  int medium = kNoMedium;  // the stretch's medium: only its photons count (kNoMedium: every photon)
};

struct VolumeEstimate {
  Color value{0.0f};   // radiance towards the ray's origin, times the transmittance from tMin
  uint32_t found = 0;  // photons that contributed
};

// sum_i T(tMin, t_i) p(dir_i . -dir) Phi_i / (pi r^2) over the photons within r of the
// stretch (t_i their projection on it; a constant kernel). radius: the beam's radius
// (0: the map's radiusFor(k); with k <= 0 too, no estimate). T is closed-form in a
// homogeneous medium, and in a grid the optical depth marched at 64 midpoints along the
// stretch, interpolated linearly (deterministic: no random numbers per gather).
VolumeEstimate volumeRadiance(const VolumePhotonMap& map, const VolumeQuery& q, const Medium& medium, int k,
                              float radius, GatherScratch& scratch);

}  // namespace penumbra
