// The beam radiance estimate over the volume map (gather/volume_estimate.h).
#include "gather/volume_estimate.h"
#include "gather/photon_map.h"

namespace penumbra {

VolumeEstimate volumeRadiance(const VolumePhotonMap&, const VolumeQuery&, const Medium&, int, float, GatherScratch&) {
  return {};  // TODO(media): the beam estimate
}

}  // namespace penumbra
