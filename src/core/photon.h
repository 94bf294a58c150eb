// Photon records as stored in the maps. Compact on purpose: 5M photons per map,
// and the normal/direction are octahedral-encoded into 32 bits each.
#pragma once
#include "core/math.h"
#include <cstdint>
#include <vector>

namespace penumbra {

// Octahedral unit-vector encoding (Cigolle et al. 2014), 16 bits per axis:
// worst-case angular error ~0.005 degrees, plenty for a "same side" test.
uint32_t encodeOctahedral(const Vec3& unit);
Vec3 decodeOctahedral(uint32_t code);

// What lies between a shadow photon and its light. Behind glass alone the light
// arrives tinted, which only a shadow ray can measure.
enum ShadowKind : uint8_t { kDirect = 0, kShadowOpaque = 1, kShadowGlass = 2 };

// A hit along a shadow photon's line: the first is direct, every later one a shadow.
struct ShadowPhoton {
  Vec3 position;
  uint32_t normal;  // octahedral geometric normal, flipped to face where the photon came from
  uint16_t light;   // index into Scene::lights
  uint8_t shadow;   // a ShadowKind: direct, behind something opaque, or behind glass only
  uint8_t pad = 0;
};

// An indirect-map photon: stored at every surface hit of a bouncing path.
struct IndirectPhoton {
  Vec3 position;
  Color power;
  uint32_t direction;  // octahedral, incoming direction of travel
  uint32_t normal;     // octahedral geometric normal, flipped to face where the photon came from
};

struct PhotonMaps {
  std::vector<ShadowPhoton> shadow;
  std::vector<IndirectPhoton> indirect;
  uint64_t emittedShadow = 0;
  uint64_t emittedIndirect = 0;
  // Converts stored indirect flux back into photon colour (a white light's photons -> 1):
  // emitted photons / (4 pi x summed luminous intensity). Used by the classic estimator.
  float classicScale = 1.0f;
};

}  // namespace penumbra
