// Hard cases, class "estimate": the resource estimate of scenes whose cost hides in
// what the scene file does not spell out. An emissive mesh at many light samples
// (one area light, a shadow ray per sample per shading point, each sample a search
// over the triangles' areas) and one OBJ instanced many times (every copy's
// triangles in the BVH). The estimate is asserted against counts derived here
// from the scene (never against a clock): rays, triangles, bytes per triangle.
#include "hard/hard_support.h"
#include "io/scene_loader.h"
#include "plan/cost_model.h"
#include "plan/job_admission.h"
#include "plan/render_plan.h"

using namespace penumbra;
using namespace penumbra::hard;

namespace {

constexpr int kThreads = 2;

ResourceEstimate estimateOf(const std::string& json, const std::vector<std::string>& overrides = {}) {
  const Scene scene = loadScene(writeTemp("scene", "json", json), overrides);
  const RenderPlan plan = makePlan(scene, parseAov(scene.render.aov));
  return admitJob(scene, plan, kThreads, false, 0).estimate;
}

// A floor lit by an emissive teapot (a mesh light of its triangles) or, for
// comparison, a quad light; physical, shadow photons only (gate on), 1 spp.
constexpr int kWidth = 80, kHeight = 50;
std::string lampJson(bool mesh) {
  const std::string light = mesh ? "" : R"({"type": "quad", "corner": [-0.3, 1.5, -0.3], "edge1": [0.6, 0, 0],
                                           "edge2": [0, 0, 0.6], "radiance": 3})";
  const std::string lamp = mesh ? R"(,
    {"type": "teapot", "material": "lamp", "subdivisions": 8, "scale": 0.3, "translate": [0, 0.8, 0]})" : "";
  return R"({"camera": {"position": [0, 1, 3], "look_at": [0, 0.5, 0], "fov": 50, "width": )" +
         std::to_string(kWidth) + R"(, "height": )" + std::to_string(kHeight) + R"(, "spp": 1},
  "lights": [)" + light + R"(],
  "materials": {"white": {"diffuse": 0.7}, "lamp": {"emission": 3}},
  "objects": [{"type": "quad", "material": "white", "corner": [-2, 0, 2], "edge1": [4, 0, 0], "edge2": [0, 0, -4]})" +
         lamp + R"(],
  "render": {"model": "physical"},
  "photons": {"gate": "on", "shadow": 100000, "global": 0, "caustic": 0}})";
}

// Shadow rays = pixels x spp x shading points per sample (1: no mirror or glass)
// x lights x samples; for a mesh light every sample is a ray, gate or not (most
// of its points are mixed, and past 64 triangles a lit verdict still samples).
TEST(HardEstimate, EmissiveMeshCountsAShadowRayPerLightSample) {
  const Scene scene = loadScene(writeTemp("lamp", "json", lampJson(true)));
  ASSERT_EQ(scene.lights.size(), 1u);
  ASSERT_EQ(scene.lights[0].type, LightType::Mesh);
  const double triangles = scene.lights[0].areaCdf.size();
  ASSERT_GT(triangles, 1000.0);
  for (int samples : {16, 256}) {
    const ResourceEstimate e = estimateOf(lampJson(true), {"render.light_samples=" + std::to_string(samples)});
    const double rays = double(kWidth) * kHeight * 1 * 1 * 1 * samples;
    EXPECT_DOUBLE_EQ(e.lightSamples, rays) << samples;
    EXPECT_DOUBLE_EQ(e.shadowRays, rays) << samples << ": the gate does not thin a mesh light's rays";
    // The time those rays and samples take: a ray, then a point found by a search
    // over log2(triangles) levels of cumulative area.
    const double perSample = cost::kRayNs + cost::kMeshLightSampleNs + cost::kMeshLightLevelNs * std::log2(1 + triangles);
    const double raySeconds = rays * perSample / kThreads * 1e-9;
    std::printf("%d samples: estimate %.3f s, of it rays and samples %.3f s\n", samples, e.renderSeconds, raySeconds);
    EXPECT_GE(e.renderSeconds, cost::kStartupSeconds + raySeconds) << samples;
    // The rest: one camera ray and one gate vote per pixel, the BVH: small.
    EXPECT_LE(e.renderSeconds, cost::kStartupSeconds + 1.1 * raySeconds + 0.05) << samples;
  }
  // A quad light at the same samples: the gate thins its rays (soft_shadows' share),
  // and its sample costs no search, so the mesh light's render is the longer by far.
  const ResourceEstimate quad = estimateOf(lampJson(false), {"render.light_samples=256"});
  const ResourceEstimate mesh = estimateOf(lampJson(true), {"render.light_samples=256"});
  EXPECT_DOUBLE_EQ(quad.lightSamples, mesh.lightSamples);
  EXPECT_NEAR(quad.shadowRays, (1 - cost::kAvoidable) * quad.lightSamples, 1.0);
  EXPECT_GT(mesh.renderSeconds - cost::kStartupSeconds, 4.0 * (quad.renderSeconds - cost::kStartupSeconds));
}

// An n x n grid of quads (2 n^2 triangles, (n + 1)^2 vertices, no normals) as OBJ text.
std::string gridObj(int n) {
  std::string obj;
  for (int i = 0; i <= n; ++i)
    for (int j = 0; j <= n; ++j) obj += "v " + num(double(i) / n) + " " + num(0.01 * ((i * 7 + j * 3) % 5)) + " " + num(double(j) / n) + "\n";
  for (int i = 0; i < n; ++i)
    for (int j = 0; j < n; ++j) {
      const int a = i * (n + 1) + j + 1, b = a + 1, c = a + n + 1, d = c + 1;
      obj += "f " + std::to_string(a) + " " + std::to_string(c) + " " + std::to_string(d) + "\nf " +
             std::to_string(a) + " " + std::to_string(d) + " " + std::to_string(b) + "\n";
    }
  return obj;
}

// `copies` mesh objects referencing the one grid file, each moved up a little.
std::string instancesJson(int copies) {
  std::string objects;
  for (int k = 0; k < copies; ++k)
    objects += R"(, {"type": "mesh", "file": "grid.obj", "material": "white", "translate": )" + vec(0, 0.01 * k, 0) + "}";
  return R"({"camera": {"position": [0.5, 2, 2], "look_at": [0.5, 0, 0.5], "width": 32, "height": 24},
  "lights": [{"type": "point", "position": [0.5, 2, 0.5], "intensity": 3}],
  "materials": {"white": {"diffuse": 0.7}},
  "objects": [{"type": "quad", "material": "white", "corner": [-2, 0, 2], "edge1": [4, 0, 0], "edge2": [0, 0, -4]})" +
         objects + R"(],
  "photons": {"shadow": 0, "indirect": 0}})";
}

// Every copy of an instanced file is its own triangles in the BVH: the estimate's
// primitives, bytes and build time grow with the copies. Bytes per triangle (the
// default layout, below kCompactBvhTriangles): the BVH (70) and its build's
// references (32), the tracer's frame (20), the scene's index (12); per vertex (0.5 a
// triangle here) the scene's positions and normals (12 each). Embree reads the
// loaded scene's indices and padded vertices in place. A render of 1.8M such
// triangles measured ~170 bytes per triangle of peak RSS.
TEST(HardEstimate, InstancedMeshesCountEveryCopysTriangles) {
  const int n = 60, copies = 40;
  writeTemp("grid", "obj", gridObj(n));
  const double perCopy = 2.0 * n * n, vertices = (n + 1.0) * (n + 1.0);
  const ResourceEstimate one = estimateOf(instancesJson(1));
  const ResourceEstimate many = estimateOf(instancesJson(copies));
  EXPECT_DOUBLE_EQ(one.primitives, perCopy + 2);  // and the floor's two
  EXPECT_DOUBLE_EQ(many.primitives, copies * perCopy + 2);
  const double added = (copies - 1) * perCopy;
  const double bytesPerTriangle = (many.bvhBytes + many.sceneBytes - one.bvhBytes - one.sceneBytes) / added;
  const double expected = 70 + 32 + 20 + 12 + (vertices / perCopy) * (12 + 12);
  std::printf("bytes per instanced triangle: %.1f (expected %.1f); build %.3f s for %.0f triangles\n",
              bytesPerTriangle, expected, many.bvhSeconds, many.primitives);
  EXPECT_NEAR(bytesPerTriangle, expected, 0.1 * expected);
  EXPECT_GT(bytesPerTriangle, 0.6 * 170) << "far below what a render measured";
  // The build: every primitive once, on the render's threads.
  EXPECT_NEAR(many.bvhSeconds, many.primitives * cost::kBvhBuildNsPerPrimitive / kThreads * 1e-9, 1e-9);
  EXPECT_GE(many.renderSeconds - one.renderSeconds, 0.9 * (many.bvhSeconds - one.bvhSeconds));
}

}  // namespace
