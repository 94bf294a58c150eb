// Whitted shading against hand-derived radiance: Lambert under directional and
// point lights, hard shadows, mirror and glass recursion (Fresnel at normal
// incidence), the depth view, the depth limit, rays born inside glass, ray-tree
// bookkeeping and NaN-free output on degenerate inputs. No photon maps: the
// ambient term is material ambient x global ambient.
#include "core/optics.h"
#include "trace/camera.h"
#include "trace/render.h"
#include "trace/shading.h"
#include "trace/trace_scene.h"
#include "io/shapes.h"
#include <gtest/gtest.h>
#include <cmath>

namespace penumbra {
namespace {

Material makeMaterial(const std::string& name, Color ambient, Color diffuse) {
  Material m;
  m.name = name;
  m.ambient = ambient;
  m.diffuse = diffuse;
  m.specular = Color(0.0f);
  return m;
}



Light directional(Vec3 travel, Color color, float intensity) {
  Light l;
  l.type = LightType::Directional;
  l.direction = glm::normalize(travel);
  l.color = color;
  l.intensity = intensity;
  return l;
}

Light point(Vec3 position, Color color, float intensity) {
  Light l;
  l.type = LightType::Point;
  l.position = position;
  l.color = color;
  l.intensity = intensity;
  return l;
}

Ray makeRay(Vec3 o, Vec3 d) {
  Ray r;
  r.origin = o;
  r.dir = glm::normalize(d);
  return r;
}

// Everything a render needs, built from a Scene owned by the caller.
struct Rig {
  explicit Rig(const Scene& s) : scene(s), tracer(s), ctx{s, tracer} {
    ctx.hasGlass = sceneHasGlass(s);
    ctx.pixelSpread = CameraRays(s.camera).pixelSpread();
  }
  Color shade(const Ray& ray, RayTree* tree = nullptr) const {
    ThreadState ts;
    ts.recorder = tree;
    return traceRay(ctx, ray, 0, Color(1.0f), 0.0f, RayKind::Camera, -1, ts);
  }
  Image render(Aov aov = Aov::Beauty) const {
    RenderOptions options;
    options.aov = aov;
    RayCounts counts;
    return renderImage(ctx, options, counts);
  }
  const Scene& scene;
  TraceScene tracer;
  ShadingContext ctx;
};

void expectColorNear(const Color& actual, const Color& expected, float tol, const std::string& what = "") {
  EXPECT_NEAR(actual.r, expected.r, tol) << what;
  EXPECT_NEAR(actual.g, expected.g, tol) << what;
  EXPECT_NEAR(actual.b, expected.b, tol) << what;
}

// Odd image sizes put the centre pixel's sample exactly on the optical axis.
Camera axisCamera(Vec3 position, Vec3 lookAt, float fov = 30.0f) {
  Camera c;
  c.position = position;
  c.lookAt = lookAt;
  c.fovY = fov;
  c.width = 65;
  c.height = 49;
  c.spp = 1;
  return c;
}

TEST(Render, LambertSphereUnderDirectionalLight) {
  Scene scene;
  scene.materials.push_back(makeMaterial("matte", Color(0.1f, 0.2f, 0.05f), Color(0.8f, 0.5f, 0.3f)));
  scene.spheres.push_back(Sphere{Vec3(0.0f), 1.0f, 0});
  const Vec3 travel = glm::normalize(Vec3(-1.0f, -1.0f, -1.0f));
  scene.lights.push_back(directional(travel, Color(1.0f, 0.9f, 0.8f), 1.5f));
  scene.render.ambient = Color(0.5f, 0.6f, 0.7f);
  scene.render.background = Color(0.01f, 0.02f, 0.03f);
  scene.camera = axisCamera(Vec3(0, 0, 5), Vec3(0.0f));
  Rig rig(scene);
  Image img = rig.render();
  ASSERT_EQ(img.width, 65);
  ASSERT_EQ(img.height, 49);

  const Material& m = scene.materials[0];
  const Color radiance = scene.lights[0].radiance();
  const Color ambient = m.ambient * scene.render.ambient;
  // Centre pixel: N = +z, L = (1,1,1)/sqrt(3).
  Color centre = ambient + m.diffuse * radiance * (1.0f / std::sqrt(3.0f));
  expectColorNear(img.at(32, 24), centre, 1e-4f, "centre pixel");

  // Every pixel against the analytic sphere (double precision), except those
  // within 1e-4 of the silhouette where hit/miss is a coin toss.
  CameraRays cam(scene.camera);
  const glm::dvec3 toLight(-glm::dvec3(travel));
  int hits = 0, misses = 0;
  for (int y = 0; y < img.height; ++y) {
    for (int x = 0; x < img.width; ++x) {
      Ray ray = cam.generate(x + 0.5f, y + 0.5f);
      glm::dvec3 o(ray.origin), d(glm::normalize(glm::dvec3(ray.dir)));
      double b = -glm::dot(o, d);
      double perp2 = glm::dot(o + b * d, o + b * d);
      if (std::abs(std::sqrt(perp2) - 1.0) < 1e-4) continue;
      Color expected = scene.render.background;
      if (perp2 < 1.0) {
        glm::dvec3 n = glm::normalize(o + (b - std::sqrt(1.0 - perp2)) * d);
        float nDotL = static_cast<float>(std::max(0.0, glm::dot(n, toLight)));
        expected = ambient + m.diffuse * radiance * nDotL;
        ++hits;
      } else {
        ++misses;
      }
      expectColorNear(img.at(x, y), expected, 1e-4f, "pixel " + std::to_string(x) + "," + std::to_string(y));
    }
  }
  EXPECT_GT(hits, 200);
  EXPECT_GT(misses, 200);
}

TEST(Render, PointLightFallsOffWithInverseSquare) {
  Scene scene;
  scene.materials.push_back(makeMaterial("matte", Color(0.1f), Color(0.8f, 0.6f, 0.4f)));
  scene.spheres.push_back(Sphere{Vec3(0.0f), 1.0f, 0});
  scene.render.ambient = Color(1.0f);
  const Ray ray = makeRay(Vec3(0, 0, 5), Vec3(0, 0, -1));  // hits (0,0,1), N = +z
  const Material& m = scene.materials[0];
  struct Case { Vec3 light; float expectedFactor; };  // N.L / d^2
  for (Case c : {Case{Vec3(0, 0, 3), 1.0f / 4.0f}, Case{Vec3(0, 0, 5), 1.0f / 16.0f},
                 Case{Vec3(0, 3, 4), (3.0f / std::sqrt(18.0f)) / 18.0f},
                 Case{Vec3(3, 0, 1), 0.0f}}) {  // grazing: N.L = 0
    scene.lights = {point(c.light, Color(1.0f), 2.0f)};
    Rig rig(scene);
    Color got = rig.shade(ray);
    expectColorNear(got, m.ambient + 2.0f * m.diffuse * c.expectedFactor, 1e-5f,
                    "light at z=" + std::to_string(c.light.z));
  }
  // Two lights add.
  scene.lights = {point(Vec3(0, 0, 3), Color(1.0f), 2.0f), point(Vec3(0, 0, 5), Color(1.0f), 2.0f)};
  Rig rig(scene);
  expectColorNear(rig.shade(ray), m.ambient + 2.0f * m.diffuse * (0.25f + 0.0625f), 1e-5f, "two lights");
}

TEST(Render, ShadowedPointIsAmbientOnly) {
  Scene scene;
  scene.materials.push_back(makeMaterial("floor", Color(0.2f, 0.1f, 0.3f), Color(0.7f)));
  scene.meshes.push_back(makeQuad(Vec3(-5, -5, 0), Vec3(10, 0, 0), Vec3(0, 10, 0), 0));  // z = 0, +z
  scene.spheres.push_back(Sphere{Vec3(0, 0, 1), 0.5f, 0});
  scene.lights.push_back(directional(Vec3(0, 0, -1), Color(1.0f), 1.0f));  // straight down
  scene.render.ambient = Color(1.0f);
  Rig rig(scene);
  const Material& m = scene.materials[0];
  const Color lit = m.ambient + m.diffuse, dark = m.ambient;
  // Oblique views of floor points (they pass beside the sphere, not through it).
  auto at = [&](float x) { return rig.shade(makeRay(Vec3(x + 3.0f, 0.0f, 3.0f), Vec3(-1, 0, -1))); };
  expectColorNear(at(0.0f), dark, 1e-6f, "under the sphere");
  expectColorNear(at(0.45f), dark, 1e-6f, "inside the shadow disc");
  expectColorNear(at(0.55f), lit, 1e-5f, "just outside the shadow disc");
  expectColorNear(at(2.0f), lit, 1e-5f, "far from the sphere");
  // A point light 3 above the sphere centre casts a wider shadow: the cone has
  // tan(alpha) = 0.5 / sqrt(9 - 0.25), so the floor disc (4 below) has radius ~0.68.
  scene.lights = {point(Vec3(0, 0, 4), Color(1.0f), 16.0f)};
  Rig rig2(scene);
  Color shadowed = rig2.shade(makeRay(Vec3(3.6f, 0.0f, 3.0f), Vec3(-1, 0, -1)));  // x = 0.6
  expectColorNear(shadowed, dark, 1e-6f, "point-light shadow");
  Color outside = rig2.shade(makeRay(Vec3(4.0f, 0.0f, 3.0f), Vec3(-1, 0, -1)));  // x = 1.0
  // d^2 = 1 + 16 = 17, N.L = 4 / sqrt(17).
  expectColorNear(outside, m.ambient + m.diffuse * 16.0f * (4.0f / std::sqrt(17.0f)) / 17.0f, 1e-5f,
                  "outside the point-light shadow");
}

// A horizontal mirror (y = 0) under a sphere at (0,1,0), r = 0.5. The camera
// ray hits the mirror at M = (0,0,2) and reflects straight at the sphere centre.
// The reflection ray starts offsetEpsilon(M) above the mirror (the documented
// offset rule), which moves its hit on the ball by ~1e-4; the analytic value
// follows that exact ray. Lambert is view independent, so the mirror shows kr x
// what a direct view of the same ball point sees.
struct MirrorScene {
  Scene scene;
  MirrorScene(float kr, int maxDepth) {
    Material mirror = makeMaterial("mirror", Color(0.05f), Color(0.0f));
    mirror.kr = kr;
    scene.materials.push_back(mirror);
    scene.materials.push_back(makeMaterial("ball", Color(0.2f, 0.3f, 0.1f), Color(0.9f, 0.5f, 0.2f)));
    scene.meshes.push_back(makeQuad(Vec3(-10, 0, -10), Vec3(0, 0, 20), Vec3(20, 0, 0), 0));  // +y
    scene.spheres.push_back(Sphere{Vec3(0, 1, 0), 0.5f, 1});
    scene.lights.push_back(directional(Vec3(0, -1, -1), Color(1.0f, 0.8f, 0.6f), 2.0f));
    scene.render.ambient = Color(0.5f);
    scene.render.maxDepth = maxDepth;
  }
  static Ray cameraRay() { return makeRay(Vec3(0, 1, 4), Vec3(0, -1, -2)); }
  // Where the reflection ray meets the ball, in double precision.
  glm::dvec3 ballHit() const {
    const Vec3 m(0, 0, 2);
    glm::dvec3 o(m.x, m.y + offsetEpsilon(m), m.z);
    glm::dvec3 d = glm::normalize(glm::dvec3(0, 1, -2));
    glm::dvec3 f = o - glm::dvec3(0, 1, 0);
    double b = -glm::dot(f, d), perp2 = glm::dot(f + b * d, f + b * d);
    return o + (b - std::sqrt(0.25 - perp2)) * d;
  }
  // Lambert radiance of the ball at p; at the exact centre-line hit N.L = 1/sqrt(10).
  Color ballRadiance(const glm::dvec3& p) const {
    const Material& b = scene.materials[1];
    glm::dvec3 n = glm::normalize(p - glm::dvec3(0, 1, 0));
    double nDotL = glm::dot(n, glm::normalize(glm::dvec3(0, 1, 1)));
    return b.ambient * scene.render.ambient +
           b.diffuse * scene.lights[0].radiance() * static_cast<float>(nDotL);
  }
  Color mirrorAmbient() const { return scene.materials[0].ambient * scene.render.ambient; }
};

TEST(Render, MirrorShowsKrTimesDirectView) {
  for (float kr : {1.0f, 0.6f}) {
    MirrorScene ms(kr, 4);
    Rig rig(ms.scene);
    RayTree tree;
    Color mirrored = rig.shade(MirrorScene::cameraRay(), &tree);
    glm::dvec3 q = ms.ballHit();
    expectColorNear(mirrored, ms.mirrorAmbient() + kr * ms.ballRadiance(q), 1e-5f,
                    "analytic, kr=" + std::to_string(kr));
    // Centre-line value N.L = 1/sqrt(10), to the offset's precision.
    Color exact = ms.ballRadiance(glm::dvec3(0, 1, 0) + 0.5 * glm::normalize(glm::dvec3(0, -1, 2)));
    expectColorNear(mirrored, ms.mirrorAmbient() + kr * exact, 1e-3f, "centre line");
    ASSERT_EQ(tree.size(), 2u);
    EXPECT_EQ(tree[1].kind, "reflection");
    EXPECT_EQ(tree[1].material, "ball");
    EXPECT_NEAR(glm::length(glm::dvec3(tree[1].position) - q), 0.0, 1e-5);
    EXPECT_NEAR(glm::length(tree[0].position - Vec3(0, 0, 2)), 0.0f, 1e-5f);
    // Look at the same ball point directly, along -z from in front of it.
    Vec3 pq(q);
    Color direct = rig.shade(makeRay(Vec3(pq.x, pq.y, 3.0f), Vec3(0, 0, -1)));
    expectColorNear(direct, ms.ballRadiance(q), 1e-5f, "direct view");
    expectColorNear(mirrored - ms.mirrorAmbient(), kr * direct, 1e-5f, "mirror = kr x direct");
  }
}

TEST(Render, MaxDepthZeroStopsReflection) {
  MirrorScene ms(1.0f, 0);
  Rig rig(ms.scene);
  RayTree tree;
  Color c = rig.shade(MirrorScene::cameraRay(), &tree);
  expectColorNear(c, ms.mirrorAmbient(), 1e-7f, "max_depth 0");
  EXPECT_EQ(tree.size(), 1u);
  // Depth 1 allows exactly one bounce.
  MirrorScene one(1.0f, 1);
  Rig rig1(one.scene);
  expectColorNear(rig1.shade(MirrorScene::cameraRay()), one.mirrorAmbient() + one.ballRadiance(one.ballHit()),
                  1e-5f, "max_depth 1");
}

// A glass slab z in [-0.5, 0.5] (ior 1.5, no ambient or diffuse of its own).
Scene slabScene(int maxDepth, Color tint, bool wallBehind, Color background) {
  Scene scene;
  Material glass = makeMaterial("glass", Color(0.0f), Color(0.0f));
  glass.transparent = true;
  glass.ior = 1.5f;
  glass.tint = tint;
  scene.materials.push_back(glass);
  scene.materials.push_back(makeMaterial("wall", Color(0.5f, 0.25f, 1.0f), Color(0.0f)));
  scene.meshes.push_back(makeBox(Vec3(-10, -10, -0.5f), Vec3(10, 10, 0.5f), 0));
  if (wallBehind) scene.meshes.push_back(makeQuad(Vec3(-20, -20, -3), Vec3(40, 0, 0), Vec3(0, 40, 0), 1));
  scene.render.ambient = Color(1.0f);
  scene.render.background = background;
  scene.render.maxDepth = maxDepth;
  return scene;
}

TEST(Render, GlassSlabAtNormalIncidence) {
  const Ray ray = makeRay(Vec3(0.1f, 0.2f, 5.0f), Vec3(0, 0, -1));
  const float R = 0.04f, T = 0.96f;  // ((1.5 - 1) / (1.5 + 1))^2
  ASSERT_NEAR(fresnelDielectric(1.0f, 1.0f, 1.5f), R, 1e-7f);
  const Color wall(0.5f, 0.25f, 1.0f);
  {
    // Depth 2: in through the front (T), out through the back (T), onto the wall.
    Scene s = slabScene(2, Color(1.0f), true, Color(0.0f));
    Rig rig(s);
    RayTree tree;
    expectColorNear(rig.shade(ray, &tree), T * T * wall, 1e-5f, "kt^2 x wall");
    // Camera, front reflection, refraction in, internal reflection, refraction out.
    ASSERT_EQ(tree.size(), 5u);
    EXPECT_TRUE(tree[0].entering);
    EXPECT_EQ(tree[1].kind, "reflection");
    EXPECT_FALSE(tree[1].hit);
    EXPECT_EQ(tree[2].kind, "refraction");
    EXPECT_FALSE(tree[2].entering);  // the back face, from inside
    EXPECT_NEAR(tree[2].t, 1.0f, 1e-4f);
    EXPECT_EQ(tree[4].kind, "refraction");
    EXPECT_EQ(tree[4].material, "wall");
  }
  {
    // Depth 4 adds the path bouncing once inside: T R R T.
    Scene s = slabScene(4, Color(1.0f), true, Color(0.0f));
    Rig rig(s);
    expectColorNear(rig.shade(ray), T * T * (1.0f + R * R) * wall, 1e-5f, "with one internal bounce");
  }
  {
    // The tint filters once, on entry.
    const Color tint(1.0f, 0.5f, 0.25f);
    Scene s = slabScene(2, tint, true, Color(0.0f));
    Rig rig(s);
    expectColorNear(rig.shade(ray), T * T * tint * wall, 1e-5f, "tinted");
  }
  const Color bg(0.2f, 0.4f, 0.6f);
  {
    // Against a uniform background: front reflection R + transmission T^2.
    Scene s = slabScene(2, Color(1.0f), false, bg);
    Rig rig(s);
    expectColorNear(rig.shade(ray), (R + T * T) * bg, 1e-5f, "background, depth 2");
  }
  {
    // With unlimited depth a clear slab in a uniform background is invisible:
    // A = R A + T B has A = B, so R B + T A = B (energy conservation).
    Scene s = slabScene(16, Color(1.0f), false, bg);
    s.render.minWeight = 0.0f;
    Rig rig(s);
    expectColorNear(rig.shade(ray), bg, 1e-5f, "background, deep");
  }
}

TEST(Render, DepthViewOrdersByDistance) {
  Scene scene;
  scene.materials.push_back(makeMaterial("m", Color(0.1f), Color(0.8f)));
  scene.spheres.push_back(Sphere{Vec3(0.0f), 1.0f, 0});
  // Wall at z = -3 over the left half of the view only.
  scene.meshes.push_back(makeQuad(Vec3(-10, -10, -3), Vec3(10, 0, 0), Vec3(0, 20, 0), 0));
  scene.camera = axisCamera(Vec3(0, 0, 5), Vec3(0.0f), 40.0f);
  Rig rig(scene);
  Image img = rig.render(Aov::Depth);
  CameraRays cam(scene.camera);
  // Nearest point: the sphere's front at t = 4 -> 0. Farthest: the wall at the
  // left corners -> 1. Misses (right corners) are white.
  Ray corner = cam.generate(0.5f, 0.5f);
  float tFar = 8.0f / -corner.dir.z;
  EXPECT_FLOAT_EQ(img.at(32, 24).r, 0.0f);
  EXPECT_NEAR(img.at(0, 0).r, 1.0f, 1e-6f);
  EXPECT_EQ(img.at(64, 0), Color(1.0f));
  EXPECT_EQ(img.at(64, 48), Color(1.0f));
  // A sphere pixel off-centre: t from the analytic hit, normalised by (4, tFar).
  Ray r = cam.generate(36.5f, 24.5f);
  glm::dvec3 o(r.origin), d(glm::normalize(glm::dvec3(r.dir)));
  double b = -glm::dot(o, d), perp2 = glm::dot(o + b * d, o + b * d);
  ASSERT_LT(perp2, 1.0);
  double t = b - std::sqrt(1.0 - perp2);
  EXPECT_NEAR(img.at(36, 24).r, (t - 4.0) / (tFar - 4.0), 1e-4);
  // Wall pixels are farther (lighter) than sphere pixels; greyscale throughout.
  EXPECT_GT(img.at(2, 24).r, img.at(32, 24).r);
  EXPECT_GT(img.at(2, 24).r, img.at(36, 24).r);
  EXPECT_NEAR(img.at(2, 24).r, (8.0f / -cam.generate(2.5f, 24.5f).dir.z - 4.0f) / (tFar - 4.0f), 1e-4f);
  for (const Color& c : img.pixels) {
    EXPECT_EQ(c.r, c.g);
    EXPECT_EQ(c.r, c.b);
    EXPECT_GE(c.r, 0.0f);
    EXPECT_LE(c.r, 1.0f);
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
    EXPECT_TRUE(r.kind == "reflection" || r.kind == "refraction") << r.kind;
  }
  // A parent's contribution is its own weighted local shading plus its children's.
  for (size_t i = 0; i < tree.size(); ++i) {
    Color rest = tree[i].contribution;
    for (const RayRecord& c : tree) {
      if (c.parent == static_cast<int>(i)) rest -= c.contribution;
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

}  // namespace
}  // namespace penumbra
