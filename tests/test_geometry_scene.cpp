// Ray queries of TraceScene against closed forms: analytic sphere hits (outside,
// inside, far from the origin, grazing), triangle hits with barycentrics,
// front/back faces and normal flipping, occlusion ranges, smooth normals and uvs.
#include "geometry/sphere_geometry.h"
#include "geometry/trace_scene.h"
#include "io/shapes.h"
#include <gtest/gtest.h>
#include <cmath>

namespace penumbra {
namespace {

Scene sceneWithSpheres(std::vector<Sphere> spheres) {
  Scene scene;
  Material m;
  m.name = "m";
  scene.materials.push_back(m);
  scene.spheres = std::move(spheres);
  return scene;
}

// Triangle (0,0,0), (1,0,0), (0,1,0) in the z = 0 plane; geometric normal +z.
Scene sceneWithTriangle(std::vector<Vec3> normals = {}, std::vector<Vec2> uvs = {}) {
  Scene scene;
  Material m;
  m.name = "m";
  scene.materials.push_back(m);
  TriangleMesh mesh;
  mesh.positions = {Vec3(0, 0, 0), Vec3(1, 0, 0), Vec3(0, 1, 0)};
  mesh.normals = std::move(normals);
  mesh.uvs = std::move(uvs);
  mesh.triangles = {{0, 1, 2}};
  scene.meshes.push_back(mesh);
  return scene;
}

Ray makeRay(Vec3 o, Vec3 d, float tMax = kInf) {
  Ray r;
  r.origin = o;
  r.dir = glm::normalize(d);
  r.tMax = tMax;
  return r;
}

TEST(SphereHit, HeadOnAndOffCentre) {
  Scene scene = sceneWithSpheres({Sphere{Vec3(0.0f), 1.0f, 0}});
  TraceScene tracer(scene);
  Hit hit;
  ASSERT_TRUE(tracer.intersect(makeRay(Vec3(0, 0, 10), Vec3(0, 0, -1)), hit));
  EXPECT_NEAR(hit.t, 9.0f, 1e-5f);
  EXPECT_EQ(hit.primId, 0u);
  for (double h : {0.1, 0.5, 0.9, 0.99, 0.9999}) {
    Ray ray = makeRay(Vec3(0.0f, static_cast<float>(h), 10.0f), Vec3(0, 0, -1));
    ASSERT_TRUE(tracer.intersect(ray, hit)) << "h=" << h;
    double hf = static_cast<float>(h);
    EXPECT_NEAR(hit.t, 10.0 - std::sqrt(1.0 - hf * hf), 2e-5) << "h=" << h;
    SurfaceRecord s = tracer.surface(ray, hit);
    EXPECT_TRUE(s.frontFace);
    EXPECT_NEAR(glm::length(s.position), 1.0f, 1e-6f);
    // Normal = (p - c) / r, facing the ray.
    EXPECT_NEAR(s.ng.y, hf, 1e-5);
    EXPECT_NEAR(s.ng.z, std::sqrt(1.0 - hf * hf), 1e-4);
    EXPECT_EQ(s.ng, s.ns);
  }
  // Misses: beside the sphere, and pointing away from it.
  EXPECT_FALSE(tracer.intersect(makeRay(Vec3(0.0f, 1.001f, 10.0f), Vec3(0, 0, -1)), hit));
  EXPECT_FALSE(tracer.intersect(makeRay(Vec3(0.0f, 0.0f, 10.0f), Vec3(0, 0, 1)), hit));
  EXPECT_FALSE(tracer.intersect(makeRay(Vec3(2.0f, 0.0f, 10.0f), Vec3(0, 0, -1)), hit));
  // A sphere entirely beyond tMax is not hit.
  EXPECT_FALSE(tracer.intersect(makeRay(Vec3(0, 0, 10), Vec3(0, 0, -1), 8.5f), hit));
}

TEST(SphereHit, RayFromInsideHitsWallFacingInwards) {
  Scene scene = sceneWithSpheres({Sphere{Vec3(1.0f, 2.0f, 3.0f), 0.75f, 0}});
  TraceScene tracer(scene);
  for (Vec3 d : {Vec3(0, 0, 1), Vec3(1, 0, 0), Vec3(-1, 2, 0.5f), Vec3(0.3f, -0.4f, -1)}) {
    Ray ray = makeRay(Vec3(1.0f, 2.0f, 3.0f), d);
    Hit hit;
    ASSERT_TRUE(tracer.intersect(ray, hit));
    EXPECT_NEAR(hit.t, 0.75f, 1e-6f);
    SurfaceRecord s = tracer.surface(ray, hit);
    EXPECT_FALSE(s.frontFace);
    // Facing the ray's origin, i.e. pointing inwards, and unit length.
    EXPECT_NEAR(glm::length(s.ng), 1.0f, 1e-6f);
    EXPECT_NEAR(glm::dot(s.ng, -ray.dir), 1.0f, 1e-5f);
    EXPECT_GT(glm::dot(s.ng, ray.origin - s.position), 0.0f);
    EXPECT_NEAR(glm::length(s.position - Vec3(1, 2, 3)), 0.75f, 1e-6f);
  }
}

TEST(SphereHit, FarAwaySphereIsAccurate) {
  const Vec3 c(1e4f, 1e4f, 1e4f);
  Scene scene = sceneWithSpheres({Sphere{c, 0.5f, 0}});
  TraceScene tracer(scene);
  Ray ray = makeRay(Vec3(0.0f), Vec3(1, 1, 1));
  Hit hit;
  ASSERT_TRUE(tracer.intersect(ray, hit));
  double expected = std::sqrt(3.0) * 1e4 - 0.5;
  EXPECT_LT(std::abs(hit.t - expected) / expected, 1e-5);
  SurfaceRecord head = tracer.surface(ray, hit);
  EXPECT_TRUE(head.frontFace);
  EXPECT_NEAR(glm::dot(head.ng, -ray.dir), 1.0f, 1e-5f);  // normal points back at the origin
  EXPECT_NEAR(glm::length(glm::dvec3(head.position) - glm::dvec3(c)), 0.5, 1e-3);
  // Slightly off-axis: perpendicular offset h = 0.3 at distance ~17320.
  Vec3 dir = glm::normalize(Vec3(1, 1, 1));
  Vec3 side = glm::normalize(Vec3(1, -1, 0));
  Vec3 origin = -0.3f * side;
  ASSERT_TRUE(tracer.intersect(makeRay(origin, dir), hit));
  double along = glm::dot(glm::dvec3(c) - glm::dvec3(origin), glm::dvec3(dir));
  double h = glm::length(glm::dvec3(c) - glm::dvec3(origin) - along * glm::dvec3(dir));
  double expected2 = along - std::sqrt(0.25 - h * h);
  EXPECT_LT(std::abs(hit.t - expected2) / expected2, 1e-5);
  SurfaceRecord s = tracer.surface(makeRay(origin, dir), hit);
  EXPECT_TRUE(s.frontFace);
  // A ray passing 0.6 to the side (radius 0.5) misses even this far out.
  EXPECT_FALSE(tracer.intersect(makeRay(-0.6f * side, dir), hit));
}

TEST(SphereHit, IntersectSphereClosedForm) {
  Sphere s{Vec3(0.0f, 0.0f, -5.0f), 2.0f, 0};
  // Unit direction: roots 3 and 7.
  EXPECT_DOUBLE_EQ(intersectSphere(s, Vec3(0.0f), Vec3(0, 0, -1), 0.0, 1e30), 3.0);
  // The nearest root inside (tMin, tMax): tMin past the first root gives the second.
  EXPECT_DOUBLE_EQ(intersectSphere(s, Vec3(0.0f), Vec3(0, 0, -1), 3.5, 1e30), 7.0);
  EXPECT_LT(intersectSphere(s, Vec3(0.0f), Vec3(0, 0, -1), 0.0, 2.5), 0.0);
  EXPECT_LT(intersectSphere(s, Vec3(0.0f), Vec3(0, 0, -1), 7.5, 1e30), 0.0);
  // A non-unit direction keeps the caller's parametrisation: t halves.
  EXPECT_DOUBLE_EQ(intersectSphere(s, Vec3(0.0f), Vec3(0, 0, -2), 0.0, 1e30), 1.5);
  // Off-axis at x = 1.2: t = 5 - sqrt(4 - 1.44) = 5 - 1.6 = 3.4.
  EXPECT_NEAR(intersectSphere(s, Vec3(1.2f, 0.0f, 0.0f), Vec3(0, 0, -1), 0.0, 1e30), 3.4, 1e-6);
  // From the centre: the wall at t = r.
  EXPECT_DOUBLE_EQ(intersectSphere(s, Vec3(0, 0, -5), Vec3(0, 1, 0), 0.0, 1e30), 2.0);
  // Miss and a zero direction.
  EXPECT_LT(intersectSphere(s, Vec3(2.01f, 0.0f, 0.0f), Vec3(0, 0, -1), 0.0, 1e30), 0.0);
  EXPECT_LT(intersectSphere(s, Vec3(0.0f), Vec3(0.0f), 0.0, 1e30), 0.0);
  // Tiny sphere far away, grazing: perpendicular distance 0.6 r.
  Sphere tiny{Vec3(0.0f, 0.0f, -1e3f), 1e-3f, 0};
  double t = intersectSphere(tiny, Vec3(6e-4f, 0.0f, 0.0f), Vec3(0, 0, -1), 0.0, 1e30);
  double x = static_cast<double>(6e-4f);
  EXPECT_NEAR(t, 1e3 - std::sqrt(1e-6 - x * x), 1e-9);
}

TEST(TriangleHit, BarycentricsAndPosition) {
  Scene scene = sceneWithTriangle();
  TraceScene tracer(scene);
  Ray ray = makeRay(Vec3(0.2f, 0.3f, 5.0f), Vec3(0, 0, -1));
  Hit hit;
  ASSERT_TRUE(tracer.intersect(ray, hit));
  EXPECT_NEAR(hit.t, 5.0f, 1e-5f);
  EXPECT_NEAR(hit.u, 0.2f, 1e-6f);  // weight of vertex 1
  EXPECT_NEAR(hit.v, 0.3f, 1e-6f);  // weight of vertex 2
  EXPECT_EQ(hit.primId, 0u);
  SurfaceRecord s = tracer.surface(ray, hit);
  EXPECT_NEAR(s.position.x, 0.2f, 1e-6f);
  EXPECT_NEAR(s.position.y, 0.3f, 1e-6f);
  EXPECT_EQ(s.position.z, 0.0f);  // barycentric interpolation is exact on the plane
  EXPECT_TRUE(s.frontFace);
  EXPECT_EQ(s.ng, Vec3(0, 0, 1));
  EXPECT_EQ(s.ns, Vec3(0, 0, 1));
  // Spherical uv fallback (no uvs): direction from the bounding-box centre (0.5,0.5,0).
  Vec2 uv = sphericalUv(glm::normalize(Vec3(-0.3f, -0.2f, 0.0f)));
  EXPECT_NEAR(s.uv.x, uv.x, 1e-6f);
  EXPECT_NEAR(s.uv.y, uv.y, 1e-6f);
  // Oblique ray: t = |o - p| along the ray.
  Vec3 o(1.0f, 1.0f, 2.0f), p(0.25f, 0.25f, 0.0f);
  ASSERT_TRUE(tracer.intersect(makeRay(o, p - o), hit));
  EXPECT_NEAR(hit.t, glm::length(p - o), 1e-5f);
  EXPECT_NEAR(hit.u, 0.25f, 1e-5f);
  EXPECT_NEAR(hit.v, 0.25f, 1e-5f);
  // Outside the triangle (x + y > 1) and parallel to it.
  EXPECT_FALSE(tracer.intersect(makeRay(Vec3(0.6f, 0.6f, 5.0f), Vec3(0, 0, -1)), hit));
  EXPECT_FALSE(tracer.intersect(makeRay(Vec3(0.2f, 0.2f, 1.0f), Vec3(1, 0, 0)), hit));
}

TEST(TriangleHit, BackFaceFlipsNormals) {
  Scene scene = sceneWithTriangle({Vec3(0, 0, 1), Vec3(0, 0, 1), Vec3(0, 0, 1)});
  TraceScene tracer(scene);
  Ray ray = makeRay(Vec3(0.2f, 0.3f, -4.0f), Vec3(0, 0, 1));
  Hit hit;
  ASSERT_TRUE(tracer.intersect(ray, hit));  // no culling: both sides are hit
  EXPECT_NEAR(hit.t, 4.0f, 1e-5f);
  SurfaceRecord s = tracer.surface(ray, hit);
  EXPECT_FALSE(s.frontFace);
  EXPECT_EQ(s.ng, Vec3(0, 0, -1));
  EXPECT_EQ(s.ns, Vec3(0, 0, -1));
}

TEST(TriangleHit, SmoothNormalsAndUvsInterpolate) {
  std::vector<Vec3> normals = {Vec3(0, 0, 1), glm::normalize(Vec3(1, 0, 1)), glm::normalize(Vec3(0, 1, 1))};
  std::vector<Vec2> uvs = {Vec2(0.1f, 0.2f), Vec2(0.9f, 0.2f), Vec2(0.1f, 0.8f)};
  Scene scene = sceneWithTriangle(normals, uvs);
  TraceScene tracer(scene);
  Ray ray = makeRay(Vec3(0.2f, 0.3f, 5.0f), Vec3(0, 0, -1));
  Hit hit;
  ASSERT_TRUE(tracer.intersect(ray, hit));
  SurfaceRecord s = tracer.surface(ray, hit);
  Vec3 expected = glm::normalize(0.5f * normals[0] + 0.2f * normals[1] + 0.3f * normals[2]);
  EXPECT_NEAR(glm::length(s.ns - expected), 0.0f, 1e-5f);
  EXPECT_EQ(s.ng, Vec3(0, 0, 1));  // the geometric normal stays flat
  EXPECT_NEAR(s.uv.x, 0.5f * 0.1f + 0.2f * 0.9f + 0.3f * 0.1f, 1e-5f);
  EXPECT_NEAR(s.uv.y, 0.5f * 0.2f + 0.2f * 0.2f + 0.3f * 0.8f, 1e-5f);
  // From behind both normals flip.
  Ray back = makeRay(Vec3(0.2f, 0.3f, -5.0f), Vec3(0, 0, 1));
  ASSERT_TRUE(tracer.intersect(back, hit));
  s = tracer.surface(back, hit);
  EXPECT_NEAR(glm::length(s.ns + expected), 0.0f, 1e-5f);
  EXPECT_EQ(s.ng, Vec3(0, 0, -1));
}

TEST(TriangleHit, ShadingNormalNeverFacesAway) {
  // Vertex normals leaning under the surface as seen from +z.
  Vec3 lean = glm::normalize(Vec3(0.6f, 0.0f, -0.8f));
  Scene scene = sceneWithTriangle({lean, lean, lean});
  TraceScene tracer(scene);
  Ray ray = makeRay(Vec3(0.2f, 0.3f, 5.0f), Vec3(0, 0, -1));
  Hit hit;
  ASSERT_TRUE(tracer.intersect(ray, hit));
  SurfaceRecord s = tracer.surface(ray, hit);
  EXPECT_TRUE(s.frontFace);
  EXPECT_EQ(s.ns, s.ng);
  EXPECT_LE(glm::dot(s.ns, ray.dir), 0.0f);
}

TEST(Occlusion, RespectsTMax) {
  Scene scene = sceneWithSpheres({Sphere{Vec3(0.0f), 1.0f, 0}});
  scene.meshes = sceneWithTriangle().meshes;
  scene.meshes[0].positions = {Vec3(-5, -5, -3), Vec3(10, -5, -3), Vec3(-5, 10, -3)};  // z = -3
  TraceScene tracer(scene);
  // Sphere front at t = 9 from z = 10.
  EXPECT_FALSE(tracer.occluded(makeRay(Vec3(0, 0, 10), Vec3(0, 0, -1), 8.9f)));
  EXPECT_TRUE(tracer.occluded(makeRay(Vec3(0, 0, 10), Vec3(0, 0, -1), 9.1f)));
  EXPECT_TRUE(tracer.occluded(makeRay(Vec3(0, 0, 10), Vec3(0, 0, -1))));
  // Beside the sphere only the triangle at t = 13 blocks.
  EXPECT_FALSE(tracer.occluded(makeRay(Vec3(1.5f, 0, 10), Vec3(0, 0, -1), 12.9f)));
  EXPECT_TRUE(tracer.occluded(makeRay(Vec3(1.5f, 0, 10), Vec3(0, 0, -1), 13.1f)));
  // tMin past the sphere's far wall (t = 11) but short of the triangle.
  Ray r = makeRay(Vec3(0, 0, 10), Vec3(0, 0, -1), 12.9f);
  r.tMin = 11.1f;
  EXPECT_FALSE(tracer.occluded(r));
  // From inside the sphere, the wall at t = 1.
  EXPECT_FALSE(tracer.occluded(makeRay(Vec3(0.0f), Vec3(0, 1, 0), 0.99f)));
  EXPECT_TRUE(tracer.occluded(makeRay(Vec3(0.0f), Vec3(0, 1, 0), 1.01f)));
  // The nearest hit agrees.
  Hit hit;
  ASSERT_TRUE(tracer.intersect(makeRay(Vec3(1.5f, 0, 10), Vec3(0, 0, -1)), hit));
  EXPECT_NEAR(hit.t, 13.0f, 1e-5f);
}

TEST(SphericalUv, CentrePolesAndSeam) {
  Vec2 front = sphericalUv(Vec3(0, 0, 1));
  EXPECT_FLOAT_EQ(front.x, 0.5f);
  EXPECT_FLOAT_EQ(front.y, 0.5f);
  EXPECT_FLOAT_EQ(sphericalUv(Vec3(0, 1, 0)).y, 0.0f);
  EXPECT_FLOAT_EQ(sphericalUv(Vec3(0, -1, 0)).y, 1.0f);
  // East (+x) is a quarter turn past the front: u = 0.75.
  EXPECT_FLOAT_EQ(sphericalUv(Vec3(1, 0, 0)).x, 0.75f);
  EXPECT_FLOAT_EQ(sphericalUv(Vec3(-1, 0, 0)).x, 0.25f);
  // Either side of the seam at -z: u stays in [0, 1) and lands at one end.
  for (Vec3 d : {Vec3(-1e-7f, 0.0f, -1.0f), Vec3(1e-7f, 0.0f, -1.0f), Vec3(0.0f, 0.0f, -1.0f),
                 Vec3(-0.0f, 0.0f, -1.0f)}) {
    Vec2 uv = sphericalUv(d);
    EXPECT_GE(uv.x, 0.0f) << d.x;
    EXPECT_LT(uv.x, 1.0f) << d.x;
    EXPECT_TRUE(uv.x < 1e-6f || uv.x > 1.0f - 1e-6f) << d.x << " -> " << uv.x;
    EXPECT_FLOAT_EQ(uv.y, 0.5f);
  }
  // Just west of the seam u is near 0, just east near 1.
  EXPECT_LT(sphericalUv(glm::normalize(Vec3(-1e-3f, 0.0f, -1.0f))).x, 1e-3f);
  EXPECT_GT(sphericalUv(glm::normalize(Vec3(1e-3f, 0.0f, -1.0f))).x, 1.0f - 1e-3f);
  // A sphere hit carries the uv of its normal.
  Scene scene = sceneWithSpheres({Sphere{Vec3(0.0f), 2.0f, 0}});
  TraceScene tracer(scene);
  Ray ray = makeRay(Vec3(0, 0, 10), Vec3(0, 0, -1));
  Hit hit;
  ASSERT_TRUE(tracer.intersect(ray, hit));
  SurfaceRecord s = tracer.surface(ray, hit);
  EXPECT_FLOAT_EQ(s.uv.x, 0.5f);
  EXPECT_FLOAT_EQ(s.uv.y, 0.5f);
  // A unit of arc moves u by 1/(2 pi r) and v by 1/(pi r).
  EXPECT_FLOAT_EQ(s.uvPerWorld.x, 1.0f / (2.0f * kPi * 2.0f));
  EXPECT_FLOAT_EQ(s.uvPerWorld.y, 1.0f / (kPi * 2.0f));
}

TEST(Geometry, QuadUvScaleFollowsItsSize) {
  // A 10 x 10 quad maps uv [0,1]^2 onto 100 units^2: 0.1 uv per unit.
  Scene scene;
  scene.materials.push_back(Material{});
  scene.meshes.push_back(makeQuad(Vec3(-5, -5, 0), Vec3(10, 0, 0), Vec3(0, 10, 0)));
  TraceScene tracer(scene);
  Hit hit;
  Ray ray = makeRay(Vec3(1, 2, 5), Vec3(0, 0, -1));
  ASSERT_TRUE(tracer.intersect(ray, hit));
  SurfaceRecord s = tracer.surface(ray, hit);
  EXPECT_NEAR(s.uv.x, 0.6f, 1e-6f);
  EXPECT_NEAR(s.uv.y, 0.7f, 1e-6f);
  EXPECT_NEAR(s.uvPerWorld.x, 0.1f, 1e-6f);
  EXPECT_NEAR(s.uvPerWorld.y, 0.1f, 1e-6f);
}

}  // namespace
}  // namespace penumbra
