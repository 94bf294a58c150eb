// Shadow photon lines against counting arguments: every line in a closed box hits one
// wall, directions are uniform over the cube's faces, a sphere blocks its solid angle
// (its far-side hits met from behind), the kind records what was crossed, and a quad
// light's lines fill its strata evenly and follow the cosine law.
#include "emit/emit.h"
#include "support/emit_fixtures.h"
#include "support/emit_box.h"
#include <gtest/gtest.h>
#include <algorithm>
#include <cmath>
#include <vector>

namespace penumbra {
namespace {

using testing::boxScene;
using testing::expectWithinSigmas;

TEST(EmitShadow, ClosedBoxEveryLineHitsExactlyOneWall) {
  const Vec3 light(0.1f, -0.2f, 0.3f);
  Scene scene = boxScene(1.0f, light, 20000);
  TraceScene tracer(scene);
  EmitOptions options;
  options.batchSize = 1000;
  EmittedPhotons maps = emitPhotons(scene, tracer, sceneEmit(scene, options));
  EXPECT_EQ(maps.emitted[MapKind::Shadow], 20000u);
  EXPECT_EQ(maps.emitted[MapKind::Indirect], 0u);
  EXPECT_TRUE(maps.batches.get<MapKind::Indirect>().empty());
  ASSERT_EQ(maps.batches.get<MapKind::Shadow>().size(), 20000u);
  for (const ShadowPhoton& p : maps.batches.get<MapKind::Shadow>()) {
    EXPECT_EQ(p.shadow, 0);
    EXPECT_EQ(p.light, 0);
    EXPECT_NEAR(maxComponent(glm::abs(p.position)), 1.0f, 1e-5f);
    // The stored normal faces the light.
    EXPECT_GT(glm::dot(decodeOctahedral(p.normal), light - p.position), 0.0f);
  }
}

TEST(EmitShadow, DirectionsAreUniformOverTheCubeFaces) {
  Scene scene = boxScene(1.0f, Vec3(0.0f), 60000);
  TraceScene tracer(scene);
  EmittedPhotons maps = emitPhotons(scene, tracer, sceneEmit(scene));
  ASSERT_EQ(maps.batches.get<MapKind::Shadow>().size(), 60000u);
  int faces[6] = {0, 0, 0, 0, 0, 0};
  for (const ShadowPhoton& p : maps.batches.get<MapKind::Shadow>()) {
    Vec3 a = glm::abs(p.position);
    int axis = a.x >= a.y && a.x >= a.z ? 0 : (a.y >= a.z ? 1 : 2);
    ++faces[2 * axis + (p.position[axis] > 0.0f ? 1 : 0)];
  }
  const double n = 60000.0, f = 1.0 / 6.0, sd = std::sqrt(n * f * (1.0 - f));
  for (int i = 0; i < 6; ++i) expectWithinSigmas(faces[i], n * f, sd, 4.0, "face " + std::to_string(i));
  // Within one face, the centre disc of radius 0.5 subtends 2 pi (1 - 1/sqrt(1.25)) / 4 pi.
  int centre = 0;
  for (const ShadowPhoton& p : maps.batches.get<MapKind::Shadow>()) {
    if (p.position.z > 0.999f && p.position.x * p.position.x + p.position.y * p.position.y < 0.25f) ++centre;
  }
  const double fc = 0.5 * (1.0 - 1.0 / std::sqrt(1.25));
  expectWithinSigmas(centre, n * fc, std::sqrt(n * fc * (1.0 - fc)), 4.0, "disc on +z");
}

TEST(EmitShadow, SphereShadowMatchesItsSolidAngle) {
  // Light at the origin, sphere at distance 1 with radius 0.5: sin(alpha) = 0.5,
  // so a line passes through it with probability (1 - cos alpha) / 2, and each
  // such line stores 3 hits: the near side (direct), far side and wall (shadow).
  Scene scene = boxScene(2.0f, Vec3(0.0f), 20000);
  scene.spheres.push_back(Sphere{Vec3(1.0f, 0.0f, 0.0f), 0.5f, 0});
  TraceScene tracer(scene);
  EmittedPhotons maps = emitPhotons(scene, tracer, sceneEmit(scene));
  size_t direct = 0, shadow = 0, onSphere = 0, shadowOnWall = 0;
  const double alpha = std::asin(0.5);
  for (const ShadowPhoton& p : maps.batches.get<MapKind::Shadow>()) {
    bool sphere = std::abs(glm::length(p.position - Vec3(1, 0, 0)) - 0.5f) < 1e-4f;
    onSphere += sphere;
    // A line meets the sphere's near side from outside and leaves its far side from inside.
    if (sphere) {
      EXPECT_EQ(bool(p.backSide), p.shadow != kDirect);
    }
    if (p.shadow) {
      ++shadow;
      // Every shadow photon is inside the sphere's shadow cone.
      double angle = std::acos(std::clamp(glm::normalize(p.position).x, -1.0f, 1.0f));
      EXPECT_LE(angle, alpha + 1e-3);
      if (!sphere) {
        ++shadowOnWall;
        EXPECT_NEAR(p.position.x, 2.0f, 1e-5f);
      }
    } else {
      ++direct;
      // Direct hits on the sphere are on the half facing the light.
      if (sphere) {
        EXPECT_LT(p.position.x, 1.0f);
      }
    }
  }
  EXPECT_EQ(direct, 20000u);  // every line's first hit
  const double n = 20000.0, f = 0.5 * (1.0 - std::cos(alpha)), sd = std::sqrt(n * f * (1.0 - f));
  expectWithinSigmas(shadow / 2.0, n * f, sd, 3.0, "lines through the sphere");
  EXPECT_EQ(shadowOnWall * 2, shadow);  // each such line: one far-side hit, one wall hit
  EXPECT_EQ(onSphere, shadow);          // near side + far side per line
  // Keeping only the first hit per line leaves exactly one (direct) photon per line.
  EmitOptions firstOnly;
  firstOnly.maxHitsPerLine = 1;
  EmittedPhotons first = emitPhotons(scene, tracer, sceneEmit(scene, firstOnly));
  ASSERT_EQ(first.batches.get<MapKind::Shadow>().size(), 20000u);
  for (const ShadowPhoton& p : first.batches.get<MapKind::Shadow>()) EXPECT_EQ(p.shadow, 0);
}

TEST(EmitShadow, ShadowKindRecordsWhetherSomethingOpaqueWasCrossed) {
  Scene scene = boxScene(2.0f, Vec3(0.0f), 40000, 0, 0.0f);
  Material glass;
  glass.name = "glass";
  glass.transparent = true;
  scene.materials.push_back(glass);
  scene.spheres.push_back(Sphere{Vec3(1.0f, 0.0f, 0.0f), 0.4f, 1});   // glass towards +x
  scene.spheres.push_back(Sphere{Vec3(-1.0f, 0.0f, 0.0f), 0.4f, 0});  // opaque towards -x
  TraceScene tracer(scene);
  EmittedPhotons maps = emitPhotons(scene, tracer, sceneEmit(scene));
  size_t glassBehind = 0, opaqueBehind = 0;
  for (const ShadowPhoton& p : maps.batches.get<MapKind::Shadow>()) {
    bool onWall = maxComponent(glm::abs(p.position)) > 1.99f;
    if (!onWall || p.shadow == kDirect) continue;
    // Wall photons in shadow sit behind one of the balls: glass ones at +x.
    if (p.position.x > 0.0f) {
      EXPECT_EQ(p.shadow, kShadowGlass);
      ++glassBehind;
    } else {
      EXPECT_EQ(p.shadow, kShadowOpaque);
      ++opaqueBehind;
    }
  }
  EXPECT_GT(glassBehind, 100u);
  EXPECT_GT(opaqueBehind, 100u);
}

// A small quad light under the lid of a closed box, facing down. Its photons start
// from one Kronecker sequence per batch: each batch's 4096 lines fill the 16 strata
// within 8 of 256 (independent starts: 15.5 in one standard deviation), and the
// floor disc below it receives the cosine law's share, R^2 / (R^2 + h^2).
TEST(EmitShadow, AQuadLightsLinesFillItsStrataEvenlyAndFollowTheCosineLaw) {
  Scene scene = boxScene(2.0f, Vec3(0.0f), 16 * 4096);
  Light quad;
  quad.type = LightType::Quad;
  quad.position = Vec3(-0.05f, 1.9f, -0.05f);
  quad.edge1 = Vec3(0.1f, 0.0f, 0.0f);
  quad.edge2 = Vec3(0.0f, 0.0f, 0.1f);  // edge1 x edge2 points down
  scene.lights = {quad};
  TraceScene tracer(scene);
  EmitOptions options;
  options.batchSize = 4096;
  const EmittedPhotons maps = emitPhotons(scene, tracer, sceneEmit(scene, options));
  ASSERT_EQ(maps.batches.get<MapKind::Shadow>().size(), 16u * 4096u);  // a closed box: one direct hit per line
  const double h = 3.9, r = 2.0;
  size_t inDisc = 0, i = 0;
  std::vector<int> strata(16, 0);
  for (const ShadowPhoton& p : maps.batches.get<MapKind::Shadow>()) {
    ++strata[p.stratum];
    if (p.position.y < -1.99f && p.position.x * p.position.x + p.position.z * p.position.z < r * r) ++inDisc;
    if (++i % 4096 == 0) {
      for (int c : strata) EXPECT_LE(std::abs(c - 256), 8) << "batch " << i / 4096;
      std::fill(strata.begin(), strata.end(), 0);
    }
  }
  const double n = 16.0 * 4096.0, f = r * r / (r * r + h * h);
  expectWithinSigmas(static_cast<double>(inDisc), n * f, std::sqrt(n * f * (1.0 - f)), 3.0, "lines into the disc");
}

}  // namespace
}  // namespace penumbra
