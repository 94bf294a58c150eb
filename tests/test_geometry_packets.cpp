// Packet queries against single rays: at every width (16, 8, 4, single fallback) each
// lane's hit and occlusion answer equals intersect's and occluded's bit for bit: camera,
// random, short, broken (NaN, out of range) rays and rays through shared edges.
#include "core/rng.h"
#include "geometry/trace_scene.h"
#include "io/shapes.h"
#include "io/teapot.h"
#include <gtest/gtest.h>
#include <cmath>
#include <cstring>

namespace penumbra {
namespace {

Scene testScene() {
  Scene scene;
  Material m;
  m.name = "m";
  scene.materials.push_back(m);
  TriangleMesh pot = makeTeapot(12);
  pot.material = 0;
  scene.meshes.push_back(pot);
  scene.meshes.push_back(makeQuad(Vec3(-3, 0, -3), Vec3(0, 0, 6), Vec3(6, 0, 0), 0));
  // Off the floor: a face coplanar with another ties everywhere, and which one a ray
  // keeps then depends on the traversal (packets do not promise to match there).
  scene.meshes.push_back(makeBox(Vec3(1.2f, 0.2f, 0.6f), Vec3(2.0f, 0.8f, 1.4f), 0));
  scene.spheres.push_back(Sphere{Vec3(-1.2f, 0.4f, 0.3f), 0.4f, 0});
  scene.spheres.push_back(Sphere{Vec3(1.0f, 1.3f, -0.5f), 0.25f, 0});
  return scene;
}

// 40x30 camera rays at the scene, then random rays, short rays, rays through shared
// edges and broken rays; 1803 in all, so the last packet of every width is partial.
std::vector<Ray> testRays() {
  std::vector<Ray> rays;
  const Vec3 eye(0.3f, 1.1f, 3.5f);
  for (int y = 0; y < 30; ++y) {
    for (int x = 0; x < 40; ++x) {
      Ray r;
      r.origin = eye;
      r.dir = glm::normalize(Vec3((x - 20) / 22.0f, (15 - y) / 22.0f - 0.3f, -1.0f));
      rays.push_back(r);
    }
  }
  Rng rng(42);
  for (int i = 0; i < 600; ++i) {
    Ray r;
    r.origin = Vec3(4.0f * rng.uniform() - 2.0f, 2.0f * rng.uniform(), 4.0f * rng.uniform() - 2.0f);
    r.dir = glm::normalize(Vec3(rng.uniform() - 0.5f, rng.uniform() - 0.5f, rng.uniform() - 0.5f));
    if (i % 3 == 0) r.tMax = 0.5f * rng.uniform();
    if (i % 7 == 0) r.tMin = 0.1f;
    rays.push_back(r);
  }
  // Aimed at the box's vertical edges and the floor quad's diagonal: rays through an
  // edge two triangles share, where both meet the ray at the same t.
  for (int i = 0; i < 200; ++i) {
    const float a = (i + 0.5f) / 200.0f;
    const Vec3 targets[3] = {Vec3(1.2f, 0.2f + 0.6f * a, 0.6f), Vec3(2.0f, 0.2f + 0.6f * a, 1.4f),
                             Vec3(-3.0f + 6.0f * a, 0.0f, -3.0f + 6.0f * a)};
    for (const Vec3& target : targets) {
      Ray r;
      r.origin = eye;
      r.dir = glm::normalize(target - eye);
      rays.push_back(r);
    }
  }
  Ray nan;
  nan.dir = Vec3(std::nanf(""), 0.0f, -1.0f);
  Ray far;
  far.origin = Vec3(3e18f, 0.0f, 0.0f);
  Ray negative;
  negative.tMin = -1.0f;
  rays.insert(rays.end(), {nan, far, negative});
  return rays;
}

bool sameHit(const Hit& a, const Hit& b) { return std::memcmp(&a, &b, sizeof(Hit)) == 0; }

TEST(PacketTrace, EveryWidthAnswersAsSingleRays) {
  Scene scene = testScene();
  TraceScene tracer(scene);
  const int native = tracer.packetWidth();
  EXPECT_TRUE(native == 1 || native == 4 || native == 8 || native == 16) << native;
  const std::vector<Ray> rays = testRays();
  const int n = static_cast<int>(rays.size());
  std::vector<Hit> single(rays.size());
  std::vector<uint8_t> singleBlocked(rays.size());
  int hits = 0;
  for (int i = 0; i < n; ++i) {
    Hit h;
    if (tracer.intersect(rays[i], h)) { single[i] = h; ++hits; }
    singleBlocked[i] = tracer.occluded(rays[i]);
  }
  EXPECT_GT(hits, 600);
  EXPECT_LT(hits, n);
  for (int width : {16, 8, 4, 1}) {
    tracer.setPacketWidth(width);
    EXPECT_LE(tracer.packetWidth(), std::max(width, 1));
    std::vector<Hit> packet(rays.size());
    std::vector<uint8_t> blocked(rays.size(), 7);
    tracer.intersectPacket(rays.data(), n, packet.data());
    tracer.occludedPacket(rays.data(), n, blocked.data());
    int differ = 0, differBlocked = 0;
    for (int i = 0; i < n; ++i) {
      if (!sameHit(packet[i], single[i])) {
        ++differ;
        ADD_FAILURE() << "ray " << i << ": packet t " << packet[i].t << " u " << packet[i].u << " v "
                      << packet[i].v << " geom " << packet[i].geomId << " prim " << packet[i].primId
                      << "; single t " << single[i].t << " u " << single[i].u << " v " << single[i].v
                      << " geom " << single[i].geomId << " prim " << single[i].primId;
      }
      if (blocked[i] != singleBlocked[i]) ++differBlocked;
    }
    EXPECT_EQ(differ, 0) << "width " << tracer.packetWidth();
    EXPECT_EQ(differBlocked, 0) << "width " << tracer.packetWidth();
  }
}

TEST(PacketTrace, EmptyAndTinyBatches) {
  Scene scene = testScene();
  TraceScene tracer(scene);
  tracer.intersectPacket(nullptr, 0, nullptr);
  tracer.occludedPacket(nullptr, 0, nullptr);
  Ray down;
  down.origin = Vec3(-2.5f, 1.0f, 2.5f);
  down.dir = Vec3(0.0f, -1.0f, 0.0f);
  Hit hit;
  uint8_t blocked = 0;
  tracer.intersectPacket(&down, 1, &hit);
  tracer.occludedPacket(&down, 1, &blocked);
  ASSERT_TRUE(hit.valid());
  EXPECT_NEAR(hit.t, 1.0f, 1e-5f);
  EXPECT_EQ(blocked, 1);
}

}  // namespace
}  // namespace penumbra
