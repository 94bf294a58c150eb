// Whitted shading against hand-derived radiance: Lambert under directional and
// point lights, hard shadows, mirror and glass recursion (Fresnel at normal
// incidence) and the depth limit. No photon maps: the ambient term is material
// ambient x global ambient.
#include "core/optics.h"
#include "io/shapes.h"
#include "support/render_fixtures.h"
#include <cmath>

namespace penumbra {
namespace {

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
// The reflection ray starts its error bound above the mirror (2^-40 of its reach),
// which moves its hit on the ball by ~1e-11; the analytic value follows that ray.
// Lambert is view independent, so the mirror shows kr x what a direct view of the
// same ball point sees.
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
    // The mirror lies in y = 0, exact in y: only the 2^-40 floor of its reach (10).
    glm::dvec3 o(m.x, m.y + 0x1p-40 * 10.0, m.z);
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
    // The ball's hit lights its point with one shadow ray; the mirror reflects no
    // light diffusely or glossily (k_d = k_s = 0), so its point needs none.
    EXPECT_EQ(tree.size(), 3u);
    tree = withoutShadowRays(tree);
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
  EXPECT_EQ(withoutShadowRays(tree).size(), 1u);
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
    // Stronger branch first: camera, refraction in, refraction out onto the
    // wall, internal reflection, and last the weak front reflection.
    ASSERT_EQ(tree.size(), 5u);
    EXPECT_TRUE(tree[0].entering);
    EXPECT_EQ(tree[1].kind, "refraction");
    EXPECT_EQ(tree[1].parent, 0);
    EXPECT_FALSE(tree[1].entering);  // the back face, from inside
    EXPECT_NEAR(tree[1].t, 1.0f, 1e-4f);
    EXPECT_EQ(tree[2].kind, "refraction");
    EXPECT_EQ(tree[2].parent, 1);
    EXPECT_EQ(tree[2].material, "wall");
    EXPECT_EQ(tree[3].kind, "reflection");
    EXPECT_EQ(tree[3].parent, 1);
    EXPECT_EQ(tree[4].kind, "reflection");
    EXPECT_EQ(tree[4].parent, 0);
    EXPECT_FALSE(tree[4].hit);
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

}  // namespace
}  // namespace penumbra
