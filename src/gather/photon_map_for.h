// The map type that stores a kind's photons: the gate's shadow map for shadow
// photons, the volume map (a grid walked along beams) for volume photons, the
// indirect map (a KD-tree with the radiance estimates) for the rest.
#pragma once
#include "core/map_kind.h"
#include <type_traits>

namespace penumbra {

class ShadowPhotonMap;
class IndirectPhotonMap;
class VolumePhotonMap;

template <class Photon>
using PhotonMapFor = std::conditional_t<
    std::is_same_v<Photon, ShadowPhoton>, ShadowPhotonMap,
    std::conditional_t<std::is_same_v<Photon, VolumePhoton>, VolumePhotonMap, IndirectPhotonMap>>;

}  // namespace penumbra
