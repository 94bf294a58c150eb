// The gate's verdicts per stratum of an area light: photons carry the stratum they
// left from (in the 20 bytes a shadow photon always took), a cell's verdict for a
// stratum at a point never contradicts brute-force visibility of that stratum, and
// soft_shadows gated stays within 0.5% of the ungated image while most rays are answered.
#include "core/light_sample.h"
#include "support/emit_fixtures.h"
#include "core/light_strata.h"
#include "emit/emit.h"
#include "gather/lookup_cache/lookup_cache.h"
#include "gather/photon_map.h"
#include "geometry/trace_scene.h"
#include "io/scene_loader.h"
#include "plan/pipeline.h"
#include "io/image_compare.h"
#include <gtest/gtest.h>
#include <cmath>

using namespace penumbra;

namespace {

const std::string kScenes = std::string(PENUMBRA_SOURCE_DIR) + "/scenes/";

TEST(GateStrata, ShadowPhotonStillTakesTwentyBytes) {
  // The stratum took the byte that was padding: a photon costs what it did.
  EXPECT_EQ(sizeof(ShadowPhoton), 20u);
  EXPECT_LE(kMaxLightStrata, 256);  // a stratum fits its byte
}

TEST(GateStrata, PhotonsAndSamplesNameTheSameStratum) {
  Light quad;
  quad.type = LightType::Quad;
  quad.position = Vec3(-0.5f, 2.0f, -0.5f);
  quad.edge1 = Vec3(1, 0, 0);
  quad.edge2 = Vec3(0, 0, 1);
  Light sphere;
  sphere.type = LightType::Sphere;
  sphere.position = Vec3(0.3f, 1.0f, -0.2f);
  sphere.radius = 0.5f;
  const SceneSphere bounds;
  const Vec3 viewer(0.1f, -2.0f, 0.4f);
  for (int i = 0; i < 16; ++i)
    for (int j = 0; j < 16; ++j) {
      const float u1 = (i + 0.37f) / 16.0f, u2 = (j + 0.61f) / 16.0f;
      // A quad's photon and a shading point's sample from the same numbers meet the
      // same point and name the same cell of the 4 x 4 grid.
      const PhotonRay p = sampleLightPhoton(quad, bounds, u1, u2, 0.5f, 0.5f);
      EXPECT_EQ(p.stratum, i / 4 + 4 * (j / 4));
      const LightIncidence in = sampleLight(quad, Vec3(0.1f, 0.0f, 0.2f), u1, u2);
      ASSERT_TRUE(in.valid);
      EXPECT_EQ(sampleStratum(quad, Vec2(u1, u2), in.point), p.stratum);
      // A sphere's sample names the stratum of the surface point it reached, as a
      // photon leaving that point does.
      const LightIncidence s = sampleLight(sphere, viewer, u1, u2);
      ASSERT_TRUE(s.valid);
      const Vec3 n = glm::normalize(s.point - sphere.position);
      EXPECT_EQ(sampleStratum(sphere, Vec2(u1, u2), s.point), sphereStratum(n));
    }
  // Equal-area cells: uniformly drawn photons fill the sphere's 16 alike.
  int counts[kMaxLightStrata] = {};
  for (int i = 0; i < 256; ++i)
    for (int j = 0; j < 256; ++j)
      ++counts[sampleLightPhoton(sphere, bounds, (i + 0.5f) / 256, (j + 0.5f) / 256, 0.5f, 0.5f).stratum];
  for (int c : counts) EXPECT_EQ(c, 256 * 256 / kMaxLightStrata);
}

// A quad light at y = 2 facing down, a floor at y = 0 and an opaque half-plane at
// y = 1 over x < 0: the floor near x = 0 sees part of the light, and for a floor
// point the line to a light point (lx, 2, lz) is blocked exactly where lx < -px.
Scene halfBlockedScene() {
  return parseScene(R"({
    "camera": {"position": [0, 3, 3], "look_at": [0, 0, 0], "width": 8, "height": 8},
    "lights": [{"type": "quad", "corner": [-0.5, 2, -0.5], "edge1": [1, 0, 0], "edge2": [0, 0, 1], "radiance": 3}],
    "materials": {"m": {"diffuse": 0.5}},
    "objects": [
      {"type": "quad", "material": "m", "corner": [-3, 0, 3], "edge1": [6, 0, 0], "edge2": [0, 0, -6]},
      {"type": "quad", "material": "m", "corner": [-3, 1, 3], "edge1": [3, 0, 0], "edge2": [0, 0, -6]}],
    "photons": {"gate": "on", "shadow": 600000}})",
                    "half_blocked.json");
}

TEST(GateStrata, StratumVerdictsAgreeWithBruteForceVisibility) {
  const Scene scene = halfBlockedScene();
  const TraceScene tracer(scene);
  EmittedPhotons maps = emitPhotons(scene, tracer, sceneEmit(scene));
  ShadowPhotonMap map;
  map.build(std::move(maps.batches.get<MapKind::Shadow>()), scene.lights.size());
  LookupCacheParams params;
  params.gate = true;
  params.cellSize = cacheCellSize(nullptr, 0, &map, params.gateParams.k, 1.5f);
  LookupCache cache;
  cache.build(&map, nullptr, params);
  ASSERT_EQ(cache.strataOf(0), kMaxLightStrata);
  const Light& light = scene.lights[0];
  const Vec3 up(0, 1, 0);
  int decided = 0, decidable = 0, mixedLight = 0;
  for (int ix = 0; ix < 41; ++ix)
    for (int iz = 0; iz < 11; ++iz) {
      const Vec3 p(-0.6f + 0.03f * ix, 0.0f, -0.3f + 0.06f * iz);
      const LookupCache::Answer a = cache.find(p, up);
      if (!a.verdicts || static_cast<GateVerdict>(a.verdicts[0]) != GateVerdict::Mixed) continue;
      ++mixedLight;
      for (int s = 0; s < kMaxLightStrata; ++s) {
        // Brute force: 6 x 6 shadow rays into the stratum's cell of the quad.
        int visible = 0, total = 0;
        for (int a1 = 0; a1 < 6; ++a1)
          for (int a2 = 0; a2 < 6; ++a2, ++total) {
            const float u1 = (s % kStrataSide + (a1 + 0.5f) / 6.0f) / kStrataSide;
            const float u2 = (s / kStrataSide + (a2 + 0.5f) / 6.0f) / kStrataSide;
            const Vec3 y = light.position + u1 * light.edge1 + u2 * light.edge2;
            Ray ray{p + 1e-4f * up, glm::normalize(y - p)};
            ray.tMax = glm::length(y - p) * 0.999f;
            if (!tracer.occluded(ray)) ++visible;
          }
        const GateVerdict v = cache.stratumVerdict(a.verdicts, 0, s, p);
        const std::string where = "at x " + std::to_string(p.x) + " z " + std::to_string(p.z) + ", stratum " +
                                  std::to_string(s) + ": " + std::to_string(visible) + " of 36 visible";
        if (visible == total) {
          EXPECT_NE(v, GateVerdict::Shadowed) << where;
        }
        if (visible == 0) {
          EXPECT_NE(v, GateVerdict::Lit) << where;
        }
        if (visible == total || visible == 0) {
          ++decidable;
          if (v != GateVerdict::Mixed) ++decided;
        }
      }
    }
  // The penumbra is there, and nearly all of its wholly lit or hidden strata are
  // answered: by the stratum's vote, or by the point's side of its split line.
  EXPECT_GT(mixedLight, 20);
  EXPECT_GT(decided, 0.9 * decidable) << decided << " of " << decidable << " decided";
}

// soft_shadows, small, in both models, at the scenes' own 4 samples per pixel: the
// gated image within 0.5% (RMSE) of the image mean of the ungated one, and under a
// twentieth of its shadow rays cast. (A split line's wrong verdicts lie in slivers
// along shadow edges, which a pixel's samples share with right ones; a single
// sample per pixel shows each sliver at full strength, about twice the error.)
void expectGatedNearUngated(const std::string& scene, int samples) {
  RenderRequest req;
  req.scenePath = kScenes + scene;
  req.overrides = {"camera.width=160", "camera.height=100", "photons.shadow=500000",
                   "render.light_samples=" + std::to_string(samples), "photons.gate=on"};
  const RenderResult gated = runRender(req);
  req.overrides.back() = "photons.gate=off";
  const RenderResult ungated = runRender(req);
  const ImageError e = compareImages(gated.image, ungated.image);
  const std::string what = scene + " at " + std::to_string(samples) + " samples";
  EXPECT_LE(e.rmse, 0.005 * e.referenceMean) << what << ": RMSE " << e.rmse << ", mean " << e.referenceMean;
  EXPECT_GT(gated.stats.cacheSplits, 0u) << what << ": no stratum answered by a split line";
  EXPECT_LT(20 * gated.stats.rays.shadow, ungated.stats.rays.shadow)
      << what << ": cast " << gated.stats.rays.shadow << " of " << ungated.stats.rays.shadow;
}

TEST(GateStrata, SoftShadowsGatedNearUngatedInBothModels) {
  expectGatedNearUngated("soft_shadows.json", 16);
  expectGatedNearUngated("soft_shadows.json", 64);
  expectGatedNearUngated("soft_shadows_physical.json", 16);
}

}  // namespace
