// The tracer's other paths: the depth and normal views, rays born inside glass, ray-tree
// bookkeeping, pixel stratification for any spp, and NaN-free output on
// degenerate inputs.
#include "core/optics.h"
#include "io/aov_display.h"
#include "io/shapes.h"
#include "support/render_fixtures.h"
#include <cmath>

namespace penumbra {
namespace {

// The depth view holds distances along the camera ray in scene units, misses 0 with
// coverage 0; its picture (io/aov_display.h) is near black, far white, misses white.
TEST(Render, DepthViewHoldsDistancesAndItsPictureOrdersThem) {
  Scene scene;
  scene.materials.push_back(makeMaterial("m", Color(0.1f), Color(0.8f)));
  scene.spheres.push_back(Sphere{Vec3(0.0f), 1.0f, 0});
  // Wall at z = -3 over the left half of the view only.
  scene.meshes.push_back(makeQuad(Vec3(-10, -10, -3), Vec3(10, 0, 0), Vec3(0, 20, 0), 0));
  scene.camera = axisCamera(Vec3(0, 0, 5), Vec3(0.0f), 40.0f);
  Rig rig(scene);
  Image img = rig.render(Aov::Depth);
  ASSERT_EQ(img.content, ImageContent::Depth);
  ASSERT_EQ(img.coverage.size(), img.pixels.size());
  CameraRays cam(scene.camera);
  Ray corner = cam.generate(0.5f, 0.5f);
  float tFar = 8.0f / -corner.dir.z;
  EXPECT_NEAR(img.at(32, 24).r, 4.0f, 4e-6f);  // the sphere's front
  EXPECT_NEAR(img.at(0, 0).r, tFar, 1e-5f);
  EXPECT_EQ(img.at(64, 0), Color(0.0f));  // misses
  EXPECT_EQ(img.coverage[64], 0.0f);
  EXPECT_EQ(img.coverage[0], 1.0f);
  // A sphere pixel off-centre: t from the analytic hit.
  Ray r = cam.generate(36.5f, 24.5f);
  glm::dvec3 o(r.origin), d(glm::normalize(glm::dvec3(r.dir)));
  double b = -glm::dot(o, d), perp2 = glm::dot(o + b * d, o + b * d);
  ASSERT_LT(perp2, 1.0);
  double t = b - std::sqrt(1.0 - perp2);
  EXPECT_NEAR(img.at(36, 24).r, t, 1e-4 * t);
  EXPECT_NEAR(img.at(2, 24).r, 8.0f / -cam.generate(2.5f, 24.5f).dir.z, 1e-4f);

  // The picture: normalised by (4, tFar), as the depth view always looked.
  Image pic = aovDisplay(img);
  EXPECT_EQ(pic.content, ImageContent::Radiance);
  EXPECT_FLOAT_EQ(pic.at(32, 24).r, 0.0f);
  EXPECT_NEAR(pic.at(0, 0).r, 1.0f, 1e-6f);
  EXPECT_EQ(pic.at(64, 0), Color(1.0f));
  EXPECT_EQ(pic.at(64, 48), Color(1.0f));
  EXPECT_NEAR(pic.at(36, 24).r, (t - 4.0) / (tFar - 4.0), 1e-4);
  EXPECT_GT(pic.at(2, 24).r, pic.at(36, 24).r);
  for (const Color& c : pic.pixels) {
    EXPECT_EQ(c.r, c.g);
    EXPECT_EQ(c.r, c.b);
    EXPECT_GE(c.r, 0.0f);
    EXPECT_LE(c.r, 1.0f);
  }
}

// With several samples, a silhouette pixel averages only the samples that hit: a miss
// must not pull its depth towards zero; it lowers the coverage instead.
TEST(Render, DepthViewIgnoresMissedSamples) {
  Scene scene;
  scene.materials.push_back(makeMaterial("m", Color(0.1f), Color(0.8f)));
  scene.spheres.push_back(Sphere{Vec3(0.0f), 1.0f, 0});
  scene.camera = axisCamera(Vec3(0, 0, 5), Vec3(0.0f), 40.0f);
  scene.camera.spp = 4;
  Rig rig(scene);
  Image img = rig.render(Aov::Depth);
  // The nearest point is the sphere's front, seen by the centre pixel; every hit is
  // farther, and no sphere point is farther than the tangent distance sqrt(24).
  const float centre = img.at(32, 24).r;
  int partial = 0;
  for (size_t i = 0; i < img.pixels.size(); ++i) {
    if (img.coverage[i] == 0.0f) continue;
    EXPECT_GE(img.pixels[i].r, centre) << i;
    EXPECT_LE(img.pixels[i].r, std::sqrt(24.0f) + 1e-4f) << i;
    partial += img.coverage[i] < 1.0f;
  }
  EXPECT_GT(partial, 0);  // the silhouette
  EXPECT_NEAR(centre, 4.0f, 0.02f);
}

// The normal view: the world-space shading normal facing the ray, in [-1, 1]; its
// picture is n * 0.5 + 0.5 weighted by coverage, misses black.
TEST(Render, NormalViewHoldsUnitNormalsAndItsPictureMapsThem) {
  Scene scene;
  scene.materials.push_back(makeMaterial("m", Color(0.1f), Color(0.8f)));
  scene.spheres.push_back(Sphere{Vec3(0.0f), 1.0f, 0});
  scene.camera = axisCamera(Vec3(0, 0, 5), Vec3(0.0f), 40.0f);
  Rig rig(scene);
  Image img = rig.render(Aov::Normal);
  ASSERT_EQ(img.content, ImageContent::Normal);
  expectColorNear(img.at(32, 24), Color(0, 0, 1), 1e-4f);
  bool negative = false;
  for (size_t i = 0; i < img.pixels.size(); ++i) {
    const Color& n = img.pixels[i];
    if (img.coverage[i] == 0.0f) { EXPECT_EQ(n, Color(0.0f)); continue; }
    EXPECT_NEAR(glm::length(n), 1.0f, 1e-4f) << i;
    negative = negative || n.x < -0.5f || n.y < -0.5f;
  }
  EXPECT_TRUE(negative);
  Image pic = aovDisplay(img);
  EXPECT_EQ(pic.at(0, 0), Color(0.0f));
  for (size_t i = 0; i < img.pixels.size(); ++i) {
    if (img.coverage[i] == 1.0f) { EXPECT_EQ(pic.pixels[i], img.pixels[i] * 0.5f + 0.5f) << i; }
  }
}

Scene glassBallScene(int maxDepth) {
  Scene scene;
  Material glass = makeMaterial("glass", Color(0.0f), Color(0.0f));
  glass.transparent = true;
  glass.ior = 1.5f;
  scene.materials.push_back(glass);
  scene.spheres.push_back(Sphere{Vec3(0.0f), 1.0f, 0});
  scene.render.background = Color(0.2f, 0.4f, 0.6f);
  scene.render.ambient = Color(1.0f);
  scene.render.maxDepth = maxDepth;
  return scene;
}

TEST(Render, RayBornInsideGlassLeavesIt) {
  Scene scene = glassBallScene(1);
  Rig rig(scene);
  const Color bg = scene.render.background;
  {
    // From the centre: normal incidence on the inside of the wall.
    RayTree tree;
    Color c = rig.shade(makeRay(Vec3(0.0f), Vec3(0, 0, 1)), &tree);
    ASSERT_TRUE(isFinite(c));
    expectColorNear(c, 0.96f * bg, 1e-5f, "leaves through the wall");
    ASSERT_GE(tree.size(), 2u);
    EXPECT_TRUE(tree[0].hit);
    EXPECT_FALSE(tree[0].entering);
    EXPECT_NEAR(tree[0].t, 1.0f, 1e-6f);
    const RayRecord* out = nullptr;
    for (const RayRecord& r : tree) {
      if (r.kind == "refraction") out = &r;
    }
    ASSERT_NE(out, nullptr);
    EXPECT_EQ(out->parent, 0);
    EXPECT_FALSE(out->hit);
    EXPECT_NEAR(out->dir.z, 1.0f, 1e-6f);
    EXPECT_GT(glm::length(out->origin), 1.0f);  // offset to the outside
  }
  {
    // Off-centre at sin(theta_i) = 0.5 inside: leaves at sin(theta_t) = 0.75.
    RayTree tree;
    Color c = rig.shade(makeRay(Vec3(0.0f, 0.5f, 0.0f), Vec3(0, 0, 1)), &tree);
    ASSERT_TRUE(isFinite(c));
    const RayRecord* out = nullptr;
    for (const RayRecord& r : tree) {
      if (r.kind == "refraction") out = &r;
    }
    ASSERT_NE(out, nullptr);
    Vec3 nOut = glm::normalize(tree[0].position);
    EXPECT_NEAR(glm::length(glm::cross(out->dir, nOut)), 0.75f, 1e-5f);
    EXPECT_GT(glm::dot(out->dir, nOut), 0.0f);
    float cosI = std::sqrt(0.75f);
    expectColorNear(c, (1.0f - fresnelDielectric(cosI, 1.5f, 1.0f)) * bg, 1e-5f, "oblique exit");
  }
  {
    // sin(theta_i) = 0.8 > 1/1.5: total internal reflection, nothing leaves.
    RayTree tree;
    Color c = rig.shade(makeRay(Vec3(0.0f, 0.8f, 0.0f), Vec3(0, 0, 1)), &tree);
    expectColorNear(c, Color(0.0f), 1e-7f, "trapped");
    for (const RayRecord& r : tree) EXPECT_NE(r.kind, "refraction");
    EXPECT_NE(tree[0].note.find("total internal reflection"), std::string::npos);
  }
}

void expectConsistentTree(const RayTree& tree) {
  ASSERT_FALSE(tree.empty());
  EXPECT_EQ(tree[0].kind, "camera");
  EXPECT_EQ(tree[0].parent, -1);
  EXPECT_EQ(tree[0].depth, 0);
  for (size_t i = 1; i < tree.size(); ++i) {
    const RayRecord& r = tree[i];
    ASSERT_GE(r.parent, 0) << i;
    ASSERT_LT(r.parent, static_cast<int>(i)) << i;
    const RayRecord& parent = tree[r.parent];
    EXPECT_TRUE(parent.hit) << i;
    EXPECT_EQ(r.depth, parent.depth + 1) << i;
    EXPECT_TRUE(r.kind == "reflection" || r.kind == "refraction" || r.kind == "shadow") << r.kind;
    if (r.kind == "shadow") {  // a transmittance in [0, 1], not radiance
      EXPECT_GE(r.contribution.r, 0.0f);
      EXPECT_LE(r.contribution.r, 1.0f);
    }
  }
  // A parent's contribution is its own weighted local shading plus its children's.
  for (size_t i = 0; i < tree.size(); ++i) {
    Color rest = tree[i].contribution;
    for (const RayRecord& c : tree) {
      if (c.parent == static_cast<int>(i) && c.kind != "shadow") rest -= c.contribution;
    }
    EXPECT_GE(rest.r, -1e-6f) << i;
    EXPECT_GE(rest.g, -1e-6f) << i;
    EXPECT_GE(rest.b, -1e-6f) << i;
  }
}

TEST(Render, TracePixelTreeIsConsistent) {
  Scene scene = glassBallScene(5);
  scene.materials.push_back(makeMaterial("floor", Color(0.1f), Color(0.7f, 0.6f, 0.5f)));
  scene.materials[1].kr = 0.5f;
  scene.meshes.push_back(makeQuad(Vec3(-10, -1.5f, -10), Vec3(0, 0, 20), Vec3(20, 0, 0), 1));
  scene.lights.push_back(point(Vec3(2, 4, 3), Color(1.0f), 20.0f));
  scene.camera = axisCamera(Vec3(0.3f, 0.5f, 5.0f), Vec3(0.0f));
  Rig rig(scene);
  Image img = rig.render();
  for (auto [x, y] : {std::pair{32, 24}, std::pair{30, 30}, std::pair{0, 48}, std::pair{64, 0}}) {
    RayTree tree = tracePixel(rig.ctx, x, y);
    expectConsistentTree(tree);
    // The root carries the pixel's value (spp 1: the same sample).
    expectColorNear(tree[0].contribution, img.at(x, y), 1e-6f, "pixel " + std::to_string(x));
  }
  RayTree centre = tracePixel(rig.ctx, 32, 24);
  EXPECT_GT(centre.size(), 4u);  // through the ball: reflections and refractions
  bool sawLeaving = false;
  for (const RayRecord& r : centre) {
    if (r.kind == "refraction" && r.hit && r.material == "glass" && !r.entering) sawLeaving = true;
  }
  EXPECT_TRUE(centre[0].entering);
  EXPECT_TRUE(sawLeaving);
  // Each shaded hit records its surface: no texture (no uv), the material's own base
  // colour, and a shading normal equal to the interpolated one (no normal map) facing
  // the ray; the floor's is +y.
  bool sawFloor = false;
  RayTree both = centre;
  for (const RayRecord& r : tracePixel(rig.ctx, 0, 48)) both.push_back(r);
  for (const RayRecord& r : both) {
    if (!r.hit || r.kind == "shadow") continue;
    EXPECT_TRUE(r.shaded);
    EXPECT_FALSE(r.hasUv);
    EXPECT_FALSE(r.metalRough);
    EXPECT_EQ(r.interpolatedNormal, r.shadingNormal);
    EXPECT_NEAR(normalTiltDegrees(r), 0.0f, 1e-3f);
    EXPECT_LT(glm::dot(r.shadingNormal, r.dir), 0.0f);
    if (r.material != "floor") continue;
    sawFloor = true;
    expectColorNear(r.baseColor, Color(0.7f, 0.6f, 0.5f), 1e-6f, "floor base colour");
    EXPECT_NEAR(r.geometricNormal.y, 1.0f, 1e-6f);
  }
  EXPECT_TRUE(sawFloor);
  EXPECT_THROW(tracePixel(rig.ctx, 65, 0), std::exception);
  EXPECT_THROW(tracePixel(rig.ctx, -1, 3), std::exception);
}

// A horizontal edge through the middle of pixel row 24 (odd height 49, so the
// optical axis sits at film y = 24.5): a white ambient-only wall fills the lower
// half of the view, the background is black. Any sampling that covers the pixel
// uniformly averages that row to 0.5.
Scene halfWallScene(int spp) {
  Scene scene;
  scene.materials.push_back(makeMaterial("white", Color(1.0f), Color(0.0f)));
  scene.meshes.push_back(makeQuad(Vec3(-50, -50, -5), Vec3(100, 0, 0), Vec3(0, 50, 0), 0));  // y <= 0
  scene.render.ambient = Color(1.0f);
  scene.camera = axisCamera(Vec3(0.0f), Vec3(0, 0, -1), 40.0f);
  scene.camera.spp = spp;
  return scene;
}

double rowMean(const Image& img, int y) {
  double sum = 0.0;
  for (int x = 0; x < img.width; ++x) sum += img.at(x, y).r;
  return sum / img.width;
}

TEST(Render, SquareSppStratifiesThePixel) {
  for (int spp : {4, 16}) {
    Scene scene = halfWallScene(spp);
    Rig rig(scene);
    Image img = rig.render();
    // A 2x2 or 4x4 grid puts exactly half the samples of every edge pixel on the wall.
    for (int x = 0; x < img.width; ++x) EXPECT_FLOAT_EQ(img.at(x, 24).r, 0.5f) << "spp " << spp << " x " << x;
    EXPECT_EQ(rowMean(img, 23), 0.0);
    EXPECT_EQ(rowMean(img, 25), 1.0);
  }
}

TEST(Render, NonSquareSppCoversThePixel) {
  for (int spp : {2, 3, 5, 8}) {
    Scene scene = halfWallScene(spp);
    Rig rig(scene);
    Image img = rig.render();
    // 65 pixels x spp samples, each on the wall with probability 1/2: sd <= 0.044
    // even without stratification.
    EXPECT_NEAR(rowMean(img, 24), 0.5, 0.12) << "spp " << spp;
  }
}

TEST(Render, DegenerateLightsProduceNoNaN) {
  Scene scene;
  scene.materials.push_back(makeMaterial("m", Color(0.1f), Color(0.8f)));
  scene.materials[0].specular = Color(0.5f);
  scene.materials[0].shininess = 20.0f;
  Material glass = makeMaterial("glass", Color(0.0f), Color(0.0f));
  glass.transparent = true;
  scene.materials.push_back(glass);
  scene.spheres.push_back(Sphere{Vec3(0.0f), 1.0f, 0});
  scene.spheres.push_back(Sphere{Vec3(1.5f, 0.5f, 0.5f), 0.4f, 1});
  scene.meshes.push_back(makeQuad(Vec3(-5, -1, -5), Vec3(0, 0, 10), Vec3(10, 0, 0), 0));  // y = -1
  scene.lights.push_back(point(Vec3(0, 0, 1), Color(1.0f), 3.0f));    // on the sphere, in view
  scene.lights.push_back(point(Vec3(2, -1, 0), Color(1.0f), 3.0f));   // on the floor
  scene.lights.push_back(point(Vec3(0, 3, 0), Color(1.0f), 0.0f));    // zero intensity
  scene.lights.push_back(directional(Vec3(0, -1, 0), Color(1.0f), 0.0f));
  scene.lights.push_back(point(Vec3(0.0f), Color(1.0f), 1.0f));       // inside the sphere
  scene.camera = axisCamera(Vec3(0, 0, 5), Vec3(0.0f), 50.0f);
  for (int spp : {1, 4}) {
    scene.camera.spp = spp;
    Rig rig(scene);
    Image img = rig.render();
    int bad = 0;
    for (const Color& c : img.pixels) bad += isFinite(c) ? 0 : 1;
    EXPECT_EQ(bad, 0) << "spp " << spp;
  }
  // The centre pixel hits the light's own position: the light is skipped, not divided by 0.
  scene.camera.spp = 1;
  Rig rig(scene);
  Color c = rig.render().at(32, 24);
  EXPECT_TRUE(isFinite(c));
  EXPECT_GE(c.r, 0.1f - 1e-6f);
}

// Nested glass at depth 64 with no weight cut-off doubles the ray tree at every
// hit; the per-sample budget must keep every pixel's tree bounded.
TEST(Render, NestedGlassTreeIsBoundedPerSample) {
  Scene scene;
  Material glass = makeMaterial("glass", Color(0.0f), Color(0.0f));
  glass.transparent = true;
  scene.materials.push_back(glass);
  scene.spheres.push_back(Sphere{Vec3(0.0f), 0.6f, 0});
  scene.meshes.push_back(makeBox(Vec3(-1.0f), Vec3(1.0f), 0));
  scene.lights.push_back(point(Vec3(2, 3, 3), Color(1.0f), 20.0f));
  scene.render.maxDepth = 64;
  scene.render.minWeight = 0.0f;
  scene.camera = axisCamera(Vec3(0, 0, 4), Vec3(0.0f));
  scene.camera.width = 9;
  scene.camera.height = 7;
  Rig rig(scene);
  RenderOptions options;
  RayCounts counts;
  Image image = renderImage(rig.ctx, options, counts);
  const uint64_t samples = 9 * 7;
  EXPECT_LE(counts.camera + counts.reflection + counts.refraction, samples * kMaxRaysPerSample);
  EXPECT_GT(counts.reflection + counts.refraction, samples * 64) << "the budget should be what stopped it";
  for (const Color& c : image.pixels) EXPECT_TRUE(isFinite(c));
}

// The non-finite guard: a NaN light (the loader refuses one; a bug could still make
// one) makes every lit sample NaN. Those samples are dropped and counted, never
// written; the unlit pixels and a finite light are untouched.
TEST(Render, NonFiniteSamplesAreDroppedAndCounted) {
  Scene scene;
  scene.materials.push_back(makeMaterial("m", Color(0.0f), Color(0.8f)));
  scene.meshes.push_back(makeQuad(Vec3(-1, -1, 0), Vec3(2, 0, 0), Vec3(0, 1, 0), 0));  // lower half only
  scene.camera = axisCamera(Vec3(0, 0, 4), Vec3(0.0f), 40.0f);
  scene.camera.width = 8;
  scene.camera.height = 8;
  scene.camera.spp = 4;
  scene.render.ambient = Color(0.0f);
  scene.lights.push_back(point(Vec3(0, 0, 3), Color(1.0f), 10.0f));
  RayCounts finiteCounts;
  const Image lit = renderImage(Rig(scene).ctx, RenderOptions{}, finiteCounts);
  EXPECT_EQ(finiteCounts.nonfiniteSamples, 0u);
  int litPixels = 0;
  for (const Color& c : lit.pixels) litPixels += c.r > 0.0f;
  ASSERT_GT(litPixels, 8);
  ASSERT_LT(litPixels, 64);

  scene.lights[0].color = Color(std::nanf(""));
  Rig rig(scene);
  RayCounts counts;
  const Image image = renderImage(rig.ctx, RenderOptions{}, counts);
  for (const Color& c : image.pixels) {
    EXPECT_TRUE(isFinite(c));
    EXPECT_EQ(c.r, 0.0f);
  }
  // Every sample that met the plane was NaN; pixels on the edge lose only some.
  EXPECT_GE(counts.nonfiniteSamples, static_cast<uint64_t>(4 * (litPixels - 8)));
  EXPECT_LE(counts.nonfiniteSamples, static_cast<uint64_t>(4 * (litPixels + 8)));
}

}  // namespace
}  // namespace penumbra
