// Photons for the lookup-cache tests: indirect photons jittered over the unit square
// and shadow photons of light 0 over it, direct on one side of an edge.
#pragma once
#include "core/photon.h"
#include "core/rng.h"

namespace penumbra::testing {

// n x n photons jittered over the unit square in the plane z = 0, facing `normal`.
inline PhotonArray<IndirectPhoton> planePhotons(int n, const Vec3& normal, const Color& power, uint64_t seed) {
  PhotonArray<IndirectPhoton> out;
  Rng rng(seed);
  for (int y = 0; y < n; ++y)
    for (int x = 0; x < n; ++x) {
      IndirectPhoton p;
      p.position = Vec3((x + rng.uniform()) / n, (y + rng.uniform()) / n, 0.0f);
      p.power = power;
      p.direction = encodeOctahedral(-normal);
      p.normal = encodeOctahedral(normal);
      out.push_back(p);
    }
  return out;
}

// Shadow photons of light 0 over the unit square: direct where x < edge, else `beyond`.
inline PhotonArray<ShadowPhoton> halfShadow(int n, float edge, uint8_t beyond, const Vec3& normal) {
  PhotonArray<ShadowPhoton> out;
  Rng rng(11);
  for (int y = 0; y < n; ++y)
    for (int x = 0; x < n; ++x) {
      ShadowPhoton p{};
      p.position = Vec3((x + rng.uniform()) / n, (y + rng.uniform()) / n, 0.0f);
      p.normal = encodeOctahedral(normal);
      p.light = 0;
      p.shadow = p.position.x < edge ? uint8_t(kDirect) : beyond;
      out.push_back(p);
    }
  return out;
}

}  // namespace penumbra::testing
