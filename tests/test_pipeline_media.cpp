// Media through the whole pipeline: a scene without a medium pays for none (no media
// counters, no volume photons, no "media" in --stats); the fog room plans, counts and
// renders the same on 1 and 2 threads; a medium in a small box is marched only by the
// rays that cross it.
#include "geometry/trace_scene.h"
#include "io/closed_mesh.h"
#include "io/media_binding.h"
#include "io/shapes.h"
#include "plan/cpu_report.h"
#include "plan/pipeline.h"
#include "trace/camera.h"
#include <gtest/gtest.h>
#include <nlohmann/json.hpp>
#include <algorithm>
#include <filesystem>
#include <fstream>

namespace penumbra {
namespace {

namespace fs = std::filesystem;
const std::string kScenes = std::string(PENUMBRA_SOURCE_DIR) + "/scenes/";

RenderResult render(const std::string& scene, std::vector<std::string> overrides, int threads = 2) {
  RenderRequest r;
  r.scenePath = scene;
  r.overrides = std::move(overrides);
  r.session.threads = threads;
  return runRender(r);
}

uint64_t mediaWork(const RayCounts& r) {
  return r.mediumSegments + r.mediumSamples + r.volumeGathers + r.volumeNeighbours + r.transmittanceRays;
}

TEST(MediaPipeline, ASceneWithoutAMediumPaysForNone) {
  const RenderResult r = render(kScenes + "cornell_physical.json",
                                {"camera.width=48", "camera.height=32", "photons.global=20000", "photons.caustic=20000"});
  EXPECT_FALSE(r.media);
  EXPECT_EQ(mediaWork(r.stats.rays), 0u);
  EXPECT_EQ(r.stats.emitted[MapKind::Volume] + r.stats.stored[MapKind::Volume], 0u);
  const nlohmann::json stats = nlohmann::json::parse(statsReport(r));
  EXPECT_FALSE(stats.contains("media"));
  EXPECT_FALSE(stats["estimate"].contains("media"));
  EXPECT_EQ(stats["plan"]["volume-photons"]["reason"], "no medium");
}

const std::vector<std::string> kQuickFog = {"camera.width=48", "camera.height=48", "photons.global=20000",
                                            "photons.caustic=20000", "photons.volume=20000", "photons.passes=2"};

TEST(MediaPipeline, TheFogRoomPlansItsVolumeMapAndCountsItsWork) {
  const RenderResult r = render(kScenes + "cornell_fog.json", kQuickFog);
  ASSERT_TRUE(r.media);
  const nlohmann::json stats = nlohmann::json::parse(statsReport(r));
  EXPECT_TRUE(stats["plan"]["volume-photons"]["on"]);
  EXPECT_EQ(stats["plan"]["volume-photons"]["reason"], "medium 'fog' scatters: 20000 photons per pass");
  ASSERT_TRUE(stats.contains("media"));
  EXPECT_TRUE(stats["estimate"].contains("media"));
  EXPECT_EQ(stats["estimate"]["media"]["camera_share"], 1.0);  // the fog fills the scene
  const RayCounts& rays = r.stats.rays;
  EXPECT_EQ(r.stats.emitted[MapKind::Volume], 2u * 20000u);  // two passes, fresh photons each
  EXPECT_GT(r.stats.stored[MapKind::Volume], 0u);
  // Every camera ray starts in the fog: at least one segment each, and a gather per segment.
  EXPECT_GE(rays.mediumSegments, rays.camera);
  EXPECT_GT(rays.mediumSamples, 0u);
  EXPECT_GT(rays.volumeGathers, 0u);
  EXPECT_GT(rays.transmittanceRays, 0u);
  EXPECT_EQ(stats["media"]["segments"], rays.mediumSegments);
  for (const Color& c : r.image.pixels) ASSERT_TRUE(std::isfinite(c.r + c.g + c.b));
}

TEST(MediaPipeline, TheFogRoomIsTheSameOnOneAndTwoThreads) {
  const RenderResult one = render(kScenes + "cornell_fog.json", kQuickFog, 1);
  const RenderResult two = render(kScenes + "cornell_fog.json", kQuickFog, 2);
  ASSERT_EQ(one.image.pixels.size(), two.image.pixels.size());
  EXPECT_TRUE(one.image.pixels == two.image.pixels);
  auto counts = [](const RenderStats& s) {
    const RayCounts& r = s.rays;
    return std::vector<uint64_t>{r.mediumSegments, r.mediumSamples,    r.volumeGathers,
                                 r.volumeNeighbours, r.transmittanceRays, s.stored[MapKind::Volume]};
  };
  EXPECT_EQ(counts(one.stats), counts(two.stats));
}

// Whether the segment a + t d, t in [0, tMax], crosses the box [lo, hi] (slabs).
bool crosses(const Vec3& a, const Vec3& d, float tMax, const Vec3& lo, const Vec3& hi) {
  float t0 = 0.0f, t1 = tMax;
  for (int i = 0; i < 3; ++i) {
    const float inv = 1.0f / d[i];
    float n = (lo[i] - a[i]) * inv, f = (hi[i] - a[i]) * inv;
    if (n > f) std::swap(n, f);
    t0 = std::max(t0, n);
    t1 = std::min(t1, f);
  }
  return t0 <= t1;
}

// A box of fog over a floor, off to one side of the view: only the camera rays that
// cross it (and the shadow rays from the floor that do) may do medium work.
TEST(MediaPipeline, AMediumInASmallBoxIsMarchedOnlyByTheRaysThatCrossIt) {
  const Vec3 lo(0.4f, 0.3f, -0.3f), hi(0.9f, 0.8f, 0.2f), light(0.0f, 3.0f, 3.0f);
  const std::string scene = R"({
  "camera": {"position": [0, 2, 4], "look_at": [0, 0, 0], "fov": 40, "width": 64, "height": 48, "spp": 1},
  "lights": [{"type": "point", "position": [0, 3, 3], "intensity": 5}],
  "media": [{"name": "fog", "sigma_a": 0.1, "sigma_s": 0.5, "g": 0}],
  "materials": {"floor": {"diffuse": 0.5}},
  "objects": [{"type": "quad", "corner": [-10, 0, 10], "edge1": [20, 0, 0], "edge2": [0, 0, -20], "material": "floor"},
              {"type": "box", "min": [0.4, 0.3, -0.3], "max": [0.9, 0.8, 0.2], "medium": "fog"}],
  "render": {"model": "physical", "max_depth": 2},
  "photons": {"gate": false, "global": 20000, "caustic": 0, "volume": 20000}})";
  const fs::path path = fs::temp_directory_path() / "penumbra_test_media_box.json";
  std::ofstream(path) << scene;
  const RenderResult r = render(path.string(), {});
  ASSERT_TRUE(r.media);

  Camera camera;
  camera.position = Vec3(0, 2, 4);
  camera.lookAt = Vec3(0.0f);
  camera.fovY = 40.0f;
  camera.width = 64;
  camera.height = 48;
  const CameraRays rays(camera);
  uint64_t cameraCrossings = 0, shadowCrossings = 0;
  for (int y = 0; y < camera.height; ++y) {
    for (int x = 0; x < camera.width; ++x) {
      const Ray ray = rays.generate(x + 0.5f, y + 0.5f);
      if (!(ray.dir.y < 0.0f)) continue;
      const float tFloor = -ray.origin.y / ray.dir.y;
      cameraCrossings += crosses(ray.origin, ray.dir, tFloor, lo, hi);
      const Vec3 p = ray.origin + tFloor * ray.dir;
      shadowCrossings += crosses(p, light - p, 1.0f, lo, hi);
    }
  }
  ASSERT_GT(cameraCrossings, 50u);
  ASSERT_LT(cameraCrossings, uint64_t(camera.width * camera.height) / 4);
  const RayCounts& c = r.stats.rays;
  EXPECT_GE(c.mediumSegments, cameraCrossings);
  EXPECT_LE(c.mediumSegments, cameraCrossings + shadowCrossings);
  EXPECT_LE(c.volumeGathers, cameraCrossings);
  // Shadow rays with a transmittance: from floor points behind the box, and the light
  // samples taken inside it.
  EXPECT_LE(c.transmittanceRays, shadowCrossings + c.mediumSamples);
  EXPECT_GT(c.mediumSamples, 0u);
  fs::remove(path);
}

// A closed mesh wound inwards (every triangle reversed) is still closed; its winding
// normal points inside, so the binding says so and a crossing ray still enters its medium.
TEST(MediaBoundaries, AMeshWoundInwardsKeepsItsInsideAndOutside) {
  const TriangleMesh box = makeBox(Vec3(-1.0f), Vec3(1.0f));
  TriangleMesh inward = box;
  for (auto& t : inward.triangles) std::swap(t[1], t[2]);
  EXPECT_EQ(openEdgeCount(inward), 0u);
  EXPECT_NEAR(signedVolume(box), 8.0, 1e-9);
  EXPECT_NEAR(signedVolume(inward), -8.0, 1e-9);
  for (bool reversed : {false, true}) {
    Scene scene;
    scene.render.model = ShadingModel::Physical;
    scene.materials.push_back(Material{});
    scene.media.push_back(Medium{});
    scene.media[0].name = "fog";
    scene.boundaryMeshes.push_back(reversed ? inward : box);
    scene.boundaryMeshes[0].media.inside = 0;
    scene.camera.position = Vec3(0.0f, 0.0f, 5.0f);
    bindMedia(scene);
    EXPECT_EQ(scene.boundaryMeshes[0].media.inward, reversed);
    EXPECT_EQ(scene.cameraMedium, kNoMedium);
    const TraceScene tracer(scene);
    TraceScene::BoundaryCrossing in, out;
    ASSERT_TRUE(tracer.nextBoundary(Ray{Vec3(0.0f, 0.0f, 5.0f), Vec3(0.0f, 0.0f, -1.0f)}, kInf, in));
    EXPECT_EQ(in.beyond, 0) << (reversed ? "inward" : "outward");
    ASSERT_TRUE(tracer.nextBoundary(Ray{Vec3(0.0f), Vec3(0.0f, 0.0f, 1.0f)}, kInf, out));
    EXPECT_EQ(out.beyond, kNoMedium) << (reversed ? "inward" : "outward");
  }
}

}  // namespace
}  // namespace penumbra
