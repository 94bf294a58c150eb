// The light seam (core/light_types.h): the type list dispatches each LightType to the
// struct that names it, a photon's start draws only the numbers its light reads, and
// the per-type answers add up to the light's power and the gate's rule.
#include "core/lights/environment_map.h"
#include "core/light_sample.h"
#include "core/rng.h"
#include "core/sampling.h"
#include <gtest/gtest.h>
#include <cmath>

namespace penumbra {
namespace {

Light lightOf(LightType type) {
  Light l;
  l.type = type;
  l.position = Vec3(0.5f, 2.0f, -1.0f);
  l.direction = Vec3(0.0f, -1.0f, 0.0f);
  l.edge1 = Vec3(1.0f, 0.0f, 0.0f);
  l.edge2 = Vec3(0.0f, 0.0f, 2.0f);  // emits towards -y
  l.radius = 0.25f;
  l.color = Color(1.0f, 0.5f, 0.25f);
  l.intensity = 3.0f;
  return l;
}

TEST(LightSeam, EveryTypeDispatchesToTheStructNamingIt) {
  for (size_t i = 0; i < kLightTypes; ++i) {
    const LightType type = static_cast<LightType>(i);
    EXPECT_EQ(dispatchLight(type, [](auto t) { return decltype(t)::kType; }), type) << i;
    const LightTraits& row = dispatchLight(type, [](auto t) -> const LightTraits& { return decltype(t)::kTraits; });
    EXPECT_EQ(&lightTraits(type), &kLightTraits[i]);
    EXPECT_EQ(lightTraits(type).support, row.support) << i;
    EXPECT_EQ(lightTraits(type).strata, row.strata) << i;
    EXPECT_EQ(lightTraits(type).aim, row.aim) << i;
  }
  EXPECT_TRUE(isDelta(LightType::Point));
  EXPECT_TRUE(isDelta(LightType::Directional));
  EXPECT_FALSE(isDelta(LightType::Quad));
  EXPECT_FALSE(isDelta(LightType::Environment));
}

// The classic photon streams must keep their order: a point light reads two numbers
// per start, every other light four, so the next number drawn is the 3rd or the 5th.
TEST(LightSeam, AClassicStartDrawsOnlyTheNumbersItsLightReads) {
  const SceneSphere bounds{Vec3(0.0f), 10.0f};
  Light spot = lightOf(LightType::Point);
  setSpotCone(spot, 0.2f, 0.4f);
  const struct {
    Light light;
    int numbers;
  } cases[] = {{lightOf(LightType::Point), 2}, {spot, 4}, {lightOf(LightType::Directional), 4},
               {lightOf(LightType::Quad), 4}, {lightOf(LightType::Sphere), 4}};
  for (const auto& c : cases) {
    EXPECT_EQ(photonStartNumbers(c.light), c.numbers);
    Rng used(7), reference(7);
    const PhotonRay r = classicPhotonStart(c.light, bounds, used);
    float u[4];
    for (int k = 0; k < c.numbers; ++k) u[k] = reference.uniform();
    EXPECT_EQ(used.uniform(), reference.uniform()) << "numbers " << c.numbers;
    // The start is the light's own photon from those numbers, its origin made safe.
    const PhotonRay same = emitterPhoton(c.light, bounds, u[0], u[1], c.numbers > 2 ? u[2] : 0.0f,
                                         c.numbers > 2 ? u[3] : 0.0f);
    EXPECT_EQ(r.origin, same.origin);
    EXPECT_EQ(r.dir, same.dir);
  }
}

// count photons of power classicPhotonPower carry the light's flux: 4 pi I for a point
// light, pi A L for a quad (A = |e1 x e2| = 2) and a sphere (A = 4 pi r^2).
TEST(LightSeam, ClassicPhotonsCarryTheLightsPower) {
  const SceneSphere bounds{Vec3(0.0f), 10.0f};
  const float count = 1000.0f;
  const double pi = 3.14159265358979323846;
  const struct {
    LightType type;
    double flux;  // per unit of color x intensity
  } cases[] = {{LightType::Point, 4.0 * pi}, {LightType::Quad, pi * 2.0}, {LightType::Sphere, pi * 4.0 * pi * 0.0625}};
  for (const auto& c : cases) {
    const Light l = lightOf(c.type);
    const Color each = classicPhotonPower(l, bounds, count);
    for (int ch = 0; ch < 3; ++ch) {
      const double expected = c.flux * l.color[ch] * l.intensity;
      EXPECT_NEAR(each[ch] * count, expected, 1e-5 * expected) << static_cast<int>(c.type) << " channel " << ch;
      EXPECT_NEAR(lightPower(l, bounds)[ch], expected, 1e-5 * expected);
    }
  }
}

// The gate answers for lights that emit shadow photons and are not dark.
TEST(LightSeam, TheGateAnswersForBrightPhotonLightsOnly) {
  EXPECT_TRUE(answersGate(lightOf(LightType::Point)));
  EXPECT_TRUE(answersGate(lightOf(LightType::Quad)));
  EXPECT_TRUE(answersGate(lightOf(LightType::Sphere)));
  EXPECT_FALSE(answersGate(lightOf(LightType::Directional)));
  EXPECT_FALSE(answersGate(makeEnvironmentLight(Color(1.0f), 1.0f, nullptr)));
  Light dark = lightOf(LightType::Quad);
  dark.intensity = 0.0f;
  EXPECT_FALSE(answersGate(dark));
}

}  // namespace
}  // namespace penumbra
