// The BVH's two leaf layouts and Embree reading the scene's own arrays: the compact
// and the default layout, over vertices shared in place or copied, answer every ray
// with the same hit, bit for bit, single rays and packets of every width alike.
#include "core/rng.h"
#include "core/sampling.h"
#include "geometry/trace_scene.h"
#include "io/scene_loader.h"
#include <gtest/gtest.h>
#include <cmath>
#include <cstring>
#include <string>
#include <vector>

namespace penumbra {
namespace {

// A wavy height field of 2 x n x n triangles over [-1, 1]^2, its last vertex at the
// end of its array (where Embree's 16-byte load reads past it).
TriangleMesh heightField(int n) {
  TriangleMesh mesh;
  for (int j = 0; j <= n; ++j)
    for (int i = 0; i <= n; ++i) {
      const float x = -1.0f + 2.0f * float(i) / float(n), z = -1.0f + 2.0f * float(j) / float(n);
      mesh.positions.emplace_back(x, 0.2f * std::sin(5.0f * x) * std::cos(4.0f * z), z);
    }
  for (int j = 0; j < n; ++j)
    for (int i = 0; i < n; ++i) {
      const uint32_t a = uint32_t(j * (n + 1) + i), b = a + 1, c = a + uint32_t(n + 1), d = c + 1;
      mesh.triangles.push_back({a, c, b});
      mesh.triangles.push_back({b, c, d});
    }
  return mesh;
}

Scene sceneWith(TriangleMesh mesh, bool padded) {
  if (padded) padVertices(mesh.positions);
  else mesh.positions.shrink_to_fit();
  Scene scene;
  scene.materials.push_back(Material{});
  scene.meshes.push_back(std::move(mesh));
  return scene;
}

// Rays from above and below at every angle, some grazing the surface.
std::vector<Ray> someRays(int count) {
  std::vector<Ray> rays;
  Rng rng(23);
  for (int i = 0; i < count; ++i) {
    const Vec3 from(2.0f * rng.uniform() - 1.0f, (i & 1) ? 1.5f : -1.5f, 2.0f * rng.uniform() - 1.0f);
    const Vec3 to(2.0f * rng.uniform() - 1.0f, 0.3f * rng.uniform() - 0.15f, 2.0f * rng.uniform() - 1.0f);
    rays.push_back(Ray{from, glm::normalize(to - from)});
  }
  return rays;
}

bool sameHit(const Hit& a, const Hit& b) {
  return a.valid() == b.valid() && (!a.valid() || (std::memcmp(&a.t, &b.t, 4) == 0 && std::memcmp(&a.u, &b.u, 4) == 0 &&
                                                   std::memcmp(&a.v, &b.v, 4) == 0 && a.primId == b.primId));
}

TEST(BvhLayout, PaddedVerticesAreReadInPlace) {
  std::vector<Vec3> v(7, Vec3(1.0f));
  EXPECT_FALSE(hasVertexPadding(v));
  padVertices(v);
  EXPECT_TRUE(hasVertexPadding(v));
  EXPECT_EQ(v.size(), 7u);
  const Vec3* data = v.data();
  padVertices(v);  // already padded: no new storage
  EXPECT_EQ(v.data(), data);
}

TEST(BvhLayout, CompactFromTheThresholdOn) {
  EXPECT_FALSE(compactBvh(kCompactBvhTriangles - 1));
  EXPECT_TRUE(compactBvh(kCompactBvhTriangles));
  EXPECT_TRUE(compactBvh(10, BvhLayout::Compact));
  EXPECT_FALSE(compactBvh(kCompactBvhTriangles, BvhLayout::Fast));
}

TEST(BvhLayout, EveryLayoutAndBufferGivesTheSameHits) {
  const TriangleMesh mesh = heightField(60);
  const Scene copied = sceneWith(mesh, false), shared = sceneWith(mesh, true);
  ASSERT_FALSE(hasVertexPadding(copied.meshes[0].positions));
  ASSERT_TRUE(hasVertexPadding(shared.meshes[0].positions));
  const TraceScene reference(copied, true, BvhLayout::Fast);
  const TraceScene fastShared(shared, true, BvhLayout::Fast), compactShared(shared, true, BvhLayout::Compact),
      compactCopied(copied, true, BvhLayout::Compact);
  const std::vector<Ray> rays = someRays(20000);
  int hits = 0;
  for (const TraceScene* t : {&fastShared, &compactShared, &compactCopied}) {
    for (size_t i = 0; i < rays.size(); ++i) {
      Hit want, got;
      const bool hit = reference.intersect(rays[i], want);
      hits += hit ? 1 : 0;
      ASSERT_EQ(t->intersect(rays[i], got), hit) << "ray " << i;
      ASSERT_TRUE(!hit || sameHit(want, got)) << "ray " << i;
      ASSERT_EQ(t->occluded(rays[i]), reference.occluded(rays[i])) << "ray " << i;
    }
    // Packets too: the tile loop's camera rays.
    std::vector<Hit> want(rays.size()), got(rays.size());
    reference.intersectPacket(rays.data(), int(rays.size()), want.data());
    t->intersectPacket(rays.data(), int(rays.size()), got.data());
    for (size_t i = 0; i < rays.size(); ++i) ASSERT_TRUE(sameHit(want[i], got[i])) << "packet ray " << i;
  }
  EXPECT_GT(hits, 3 * 20000 * 9 / 10);  // most rays meet the surface
}

// The shipped mesh scenes, rays from the camera into the scene's bounds and shadow
// rays from their hits to the first light, at every packet width: each query kind
// answers alike in both layouts (the compact BVH's occlusion packets take Embree's
// incoherent kernel, whose coherent one for robust compact leaves never returns).
TEST(BvhLayout, ShippedMeshScenesAnswerAlikeInBothLayouts) {
  for (const char* name : {"fig05_reflective_mesh.json", "soft_shadows.json", "showcase.json"}) {
    const Scene scene = loadScene(std::string(PENUMBRA_SOURCE_DIR) + "/scenes/" + name);
    ASSERT_FALSE(scene.lights.empty()) << name;
    TraceScene fast(scene, true, BvhLayout::Fast), compact(scene, true, BvhLayout::Compact);
    const SceneSphere bounds = fast.boundingSphere();
    Rng rng(5);
    std::vector<Ray> camera, shadow;
    for (int i = 0; i < 4096; ++i) {
      const Vec3 to = bounds.center + bounds.radius * uniformSphere(rng.uniform(), rng.uniform()) * rng.uniform();
      const Ray ray{scene.camera.position, glm::normalize(to - scene.camera.position)};
      camera.push_back(ray);
      Hit hit;
      if (!fast.intersect(ray, hit)) continue;
      const SurfaceRecord s = fast.surface(ray, hit, kSurfaceGeometric);
      const Vec3 d = scene.lights[0].position - s.position;
      Ray toLight{spawnOrigin(s, glm::normalize(d)), glm::normalize(d)};
      toLight.tMax = glm::length(d) * 0.999f;
      shadow.push_back(toLight);
    }
    for (int width : {16, 8, 4}) {
      fast.setPacketWidth(width);
      compact.setPacketWidth(width);
      std::vector<Hit> want(camera.size()), got(camera.size());
      fast.intersectPacket(camera.data(), int(camera.size()), want.data());
      compact.intersectPacket(camera.data(), int(camera.size()), got.data());
      std::vector<uint8_t> blockedFast(shadow.size()), blockedCompact(shadow.size());
      fast.occludedPacket(shadow.data(), int(shadow.size()), blockedFast.data());
      compact.occludedPacket(shadow.data(), int(shadow.size()), blockedCompact.data());
      for (size_t i = 0; i < camera.size(); ++i) ASSERT_TRUE(sameHit(want[i], got[i])) << name << " ray " << i;
      for (size_t i = 0; i < shadow.size(); ++i) {
        ASSERT_EQ(blockedFast[i], blockedCompact[i]) << name << " shadow ray " << i << ", width " << width;
        ASSERT_EQ(bool(blockedCompact[i]), compact.occluded(shadow[i])) << name << " shadow ray " << i;
      }
    }
  }
}

}  // namespace
}  // namespace penumbra
