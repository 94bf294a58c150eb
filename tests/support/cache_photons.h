// Photons for the gather and lookup-cache tests: indirect photons on the plane z = 0
// (jittered over the unit square, or one at a time) and the white Lambertian surface
// that reads them, and shadow photons of light 0, direct on one side of an edge.
#pragma once
#include "core/bsdf.h"
#include "core/photon.h"
#include "core/rng.h"

namespace penumbra::testing {

// One indirect photon at `position` arriving along -normal on a surface facing `normal`.
inline IndirectPhoton planePhoton(const Vec3& position, const Vec3& normal, const Color& power) {
  IndirectPhoton p;
  p.position = position;
  p.power = power;
  p.direction = encodeOctahedral(-normal);
  p.normal = encodeOctahedral(normal);
  return p;
}

// Albedo 1, Lambertian: a photon estimate reads irradiance / pi.
inline Bsdf whiteLambertian() {
  Bsdf b;
  b.type = BsdfType::Opaque;
  b.diffuse = Color(1.0f);
  return b;
}

// n x n photons jittered over the unit square in the plane z = 0, facing `normal`.
inline PhotonArray<IndirectPhoton> planePhotons(int n, const Vec3& normal, const Color& power, uint64_t seed) {
  PhotonArray<IndirectPhoton> out;
  Rng rng(seed);
  for (int y = 0; y < n; ++y)
    for (int x = 0; x < n; ++x) {
      const float px = (x + rng.uniform()) / n, py = (y + rng.uniform()) / n;
      out.push_back(planePhoton(Vec3(px, py, 0.0f), normal, power));
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
