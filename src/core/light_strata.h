// The strata of an area light that the shadow gate votes on separately: a quad's or
// disk's 4x4 cells of its (u, v) parameters (the grid render.light_samples stratifies),
// a sphere's 4x4 equal-area cells of its surface; every other light is one stratum.
#pragma once
#include "core/scene.h"
#include <cmath>
#include <cstdint>

namespace penumbra {

constexpr int kStrataSide = 4;
constexpr int kMaxLightStrata = kStrataSide * kStrataSide;

// How many strata the gate keeps for a light (its traits' StrataKind).
inline int lightStrata(const Light& light) {
  return lightTraits(light.type).strata != StrataKind::One ? kMaxLightStrata : 1;
}

// The cell of (u1, u2) in [0, 1)^2 (NaN and out-of-range values clamp to an edge cell).
inline uint8_t stratumOf(float u1, float u2) {
  const float top = static_cast<float>(kStrataSide - 1), side = static_cast<float>(kStrataSide);
  // fmax/fmin's clamp (NaN to 0) written out, so no library call runs per photon.
  auto cell = [&](float u) {
    const float x = u * side > 0.0f ? u * side : 0.0f;
    return static_cast<int>(x < top ? x : top);
  };
  const int i = cell(u1), j = cell(u2);
  return static_cast<uint8_t>(i + kStrataSide * j);
}

// A sphere light's stratum at the unit outward normal n: uniformSphere's (u1, u2)
// inverted, so cells have equal area and do not depend on who looks at the sphere.
// Four bins of phi are its quadrants, read from the signs of x and y (no atan2 on
// every sample of a mixed sphere light).
static_assert(kStrataSide == 4, "sphereStratum's phi bins are the quadrants");
inline uint8_t sphereStratum(const Vec3& n) {
  const int quadrant = n.y >= 0.0f ? (n.x >= 0.0f ? 0 : 1) : (n.x < 0.0f ? 2 : 3);
  return static_cast<uint8_t>(stratumOf(0.5f * (1.0f - n.z), 0.0f) + kStrataSide * quadrant);
}

// The stratum of one light sample drawn with numbers u that reached `point` on the
// light, by its StrataKind: Parametric from u itself (u is the light's (u, v)), Surface
// (the sphere) from where it was met. Inline: the gate asks once per light sample.
inline uint8_t sampleStratum(const Light& light, const Vec2& u, const Vec3& point) {
  switch (lightTraits(light.type).strata) {
    case StrataKind::Parametric: return stratumOf(u.x, u.y);
    case StrataKind::Surface: return sphereStratum(glm::normalize(point - light.position));
    case StrataKind::One: break;
  }
  return 0;
}

}  // namespace penumbra
