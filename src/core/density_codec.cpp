// Loads the OpenVDB module on first use (core/module_loader.h).
#include "core/density_codec.h"

#include "core/module_loader.h"

#ifndef PENUMBRA_VOLUME_MODULE
#define PENUMBRA_VOLUME_MODULE nullptr
#endif

namespace penumbra {

const DensityCodec& densityCodec() {
  static const DensityCodec* const codec =
      moduleObject<DensityCodec>(kVolumeModuleName, kDensityCodecEntry, PENUMBRA_VOLUME_MODULE, "OpenVDB");
  return *codec;
}

}  // namespace penumbra
