// Invisible medium boundaries: their own Embree scene, crossed by nextBoundary with the
// medium beyond, never seen by surface queries; a scene without them builds none.
#include "geometry/trace_scene.h"
#include "io/shapes.h"
#include "support/scene_fixtures.h"
#include <gtest/gtest.h>

namespace penumbra {
namespace {

Medium fog() {
  Medium m;
  m.name = "fog";
  m.sigmaA = Color(0.1f);
  m.sigmaS = Color(0.2f);
  return m;
}

Scene boxOfFog() {
  Scene scene;
  scene.media.push_back(fog());
  TriangleMesh box = makeBox(Vec3(-1.0f), Vec3(1.0f), 0);
  box.media = {0, kNoMedium, true};
  scene.boundaryMeshes.push_back(box);
  scene.boundarySpheres.push_back(Sphere{Vec3(5.0f, 0.0f, 0.0f), 0.5f, 0, {0, kNoMedium, true}});
  return scene;
}

TEST(GeometryMedia, BoxBoundaryIsEnteredThenLeft) {
  // A ray along +z through the box [-1, 1]^3 from z = -4: in at t = 3, out at t = 5.
  const Scene scene = boxOfFog();
  const TraceScene tracer(scene);
  ASSERT_TRUE(tracer.hasBoundaries());
  const Ray ray = makeRay(Vec3(0.2f, 0.3f, -4.0f), Vec3(0, 0, 1));
  TraceScene::BoundaryCrossing in, out;
  ASSERT_TRUE(tracer.nextBoundary(ray, kInf, in));
  EXPECT_NEAR(in.t, 3.0f, 1e-5f);
  EXPECT_EQ(in.beyond, 0);
  const Ray next{spawnOrigin(in.surface, ray.dir), ray.dir};
  ASSERT_TRUE(tracer.nextBoundary(next, kInf, out));
  EXPECT_NEAR(glm::dot(next.origin - ray.origin, ray.dir) + out.t, 5.0f, 1e-5f);
  EXPECT_EQ(out.beyond, kNoMedium);
  // Short of the box: nothing; surface queries never see a boundary.
  EXPECT_FALSE(tracer.nextBoundary(ray, 2.9f, in));
  Hit hit;
  EXPECT_FALSE(tracer.intersect(ray, hit));
  EXPECT_FALSE(tracer.occluded(ray));
}

TEST(GeometryMedia, SphereBoundaryFromInsideLeavesToTheOutside) {
  const Scene scene = boxOfFog();
  const TraceScene tracer(scene);
  const Ray ray = makeRay(Vec3(5.0f, 0.0f, 0.0f), Vec3(0, 1, 0));
  TraceScene::BoundaryCrossing c;
  ASSERT_TRUE(tracer.nextBoundary(ray, kInf, c));
  EXPECT_NEAR(c.t, 0.5f, 1e-5f);
  EXPECT_EQ(c.beyond, kNoMedium);
  const Ray in = makeRay(Vec3(5.0f, -3.0f, 0.0f), Vec3(0, 1, 0));
  ASSERT_TRUE(tracer.nextBoundary(in, kInf, c));
  EXPECT_NEAR(c.t, 2.5f, 1e-5f);
  EXPECT_EQ(c.beyond, 0);
}

TEST(GeometryMedia, SceneWithoutBoundariesBuildsNone) {
  Scene scene;
  scene.meshes.push_back(makeBox(Vec3(-1.0f), Vec3(1.0f), 0));
  const TraceScene tracer(scene);
  EXPECT_FALSE(tracer.hasBoundaries());
  TraceScene::BoundaryCrossing c;
  EXPECT_FALSE(tracer.nextBoundary(makeRay(Vec3(0, 0, -4), Vec3(0, 0, 1)), kInf, c));
}

TEST(GeometryMedia, MediumBeyondAClosedSurface) {
  // A sphere with fog inside in a vacuum scene: entering gives the fog, leaving vacuum;
  // an open surface (separates false) keeps the ray's medium.
  Scene scene;
  scene.media.push_back(fog());
  scene.spheres.push_back(Sphere{Vec3(0.0f), 1.0f, 0, {0, kNoMedium, true}});
  scene.materials.push_back(Material{});
  const TraceScene tracer(scene);
  const Ray ray = makeRay(Vec3(0, 0, -4), Vec3(0, 0, 1));
  Hit hit;
  ASSERT_TRUE(tracer.intersect(ray, hit));
  const SurfaceRecord s = tracer.surface(ray, hit, kSurfaceGeometric);
  EXPECT_EQ(tracer.mediumBeyond(hit, s, ray.dir, kNoMedium), 0);
  EXPECT_EQ(tracer.mediumBeyond(hit, s, -ray.dir, kNoMedium), kNoMedium);
  scene.spheres[0].media.separates = false;
  EXPECT_EQ(tracer.mediumBeyond(hit, s, ray.dir, 3), 3);
}

}  // namespace
}  // namespace penumbra
