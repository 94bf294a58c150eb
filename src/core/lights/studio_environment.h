// The built-in studio environment: a gradient sky over a darker ground with one soft
// key lobe, generated as a lat-long map (so it is importance-sampled like any map),
// its constants, and the grey camera rays see behind a model lit by it.
#pragma once
#include "core/lights/environment_map.h"

namespace penumbra {

// The studio's radiance along unit w (y up), a sum of terms whose integrals are closed
// forms (docs/scene-format.md, "environment"):
//   L(w) = kGround + (kHorizon - kGround) [w.y > 0] + kZenith max(0, w.y) + kKey f(w . key)
//   f(t) = ((t - c) / (1 - c))^2 for t > c = cos(kKeyRadius), else 0
namespace studio {
constexpr double kGround = 0.3;    // below the horizon
constexpr double kHorizon = 0.8;   // just above it
constexpr double kZenith = 0.4;    // times w.y: the sky is 1.2 straight up
constexpr double kKey = 15.0;      // the key lobe's peak, added at its centre
constexpr double kKeyRadiusDegrees = 20.0;
// The key is 45 degrees up, turned 30 degrees from +z towards -x: to the left of the
// framing camera, which looks from +z turned 30 degrees towards +x.
constexpr double kKeyAzimuthDegrees = -30.0;
constexpr double kKeyElevationDegrees = 45.0;
constexpr int kWidth = 512, kHeight = 256;  // the map: 0.7 degrees a texel, 2 MB with its tables
constexpr float kBackground = 0.18f;        // middle grey: what camera rays see where nothing is
}  // namespace studio

// The key lobe's centre, a unit vector.
glm::dvec3 studioKeyDirection();

// L(w) as defined above (w unit).
double studioRadiance(const glm::dvec3& w);

// The studio as a kWidth x kHeight map turned by `rotationDegrees` about +y; each texel
// holds L averaged over its solid angle (exactly for the sky and ground terms, the key
// from 4 x 4 equal-area samples), so the map's integrals match the closed forms.
std::shared_ptr<const EnvironmentMap> makeStudioMap(float rotationDegrees);

// Appends the studio (its map times color x intensity) as `scene`'s environment, and
// kBackground as what camera rays see of it.
void addStudioEnvironment(Scene& scene, const Color& color, float intensity, float rotationDegrees);

}  // namespace penumbra
