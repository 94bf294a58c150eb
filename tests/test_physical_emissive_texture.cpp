// Textured and two-sided mesh lights: samples drawn by area x texel luminance against a
// brute-force integral of the texture's radiance, photons carrying each channel's
// power, a mostly-dark texture that glows without lighting, and an emitter that also
// reflects (glTF's model).
#include "core/emission_map.h"
#include "core/lights/emissive_mesh.h"
#include "io/image_io.h"
#include "io/scene_sections.h"
#include "support/physical_fixtures.h"
#include "support/scratch_dir.h"

namespace penumbra {
namespace {

// A 2 x 1 quad at height 2 facing down (triangles wound for -y), u = x / 2, v = z.
const std::vector<Vec3> kTriangles = {Vec3(0, 2, 0), Vec3(2, 2, 0), Vec3(0, 2, 1),
                                      Vec3(2, 2, 0), Vec3(2, 2, 1), Vec3(0, 2, 1)};
const std::vector<Vec2> kUvs = {Vec2(0, 0), Vec2(1, 0), Vec2(0, 1), Vec2(1, 0), Vec2(1, 1), Vec2(0, 1)};

// 4 x 2 texels with black cells, bright cells and colour.
EmissionMap checkerMap() {
  EmissionMap map;
  map.width = 4;
  map.height = 2;
  map.texels = {Color(0.0f), Color(0.0f), Color(4.0f, 2.0f, 1.0f), Color(1.0f),
                Color(0.0f), Color(0.0f, 2.0f, 0.0f), Color(0.0f), Color(0.5f)};
  return map;
}

// Midpoint sums over an n x n grid of the quad: the emitted radiance's integral
// weighted by `f(point, radiance)`.
template <class F>
Color integrateQuad(const EmissionMap& map, int n, F f) {
  Color sum(0.0f);
  const float cell = 1.0f / float(n);
  for (int i = 0; i < n; ++i) {
    for (int j = 0; j < n; ++j) {
      const float u = (float(i) + 0.5f) * cell, v = (float(j) + 0.5f) * cell;
      sum += f(Vec3(2.0f * u, 2.0f, v), map.at(Vec2(u, v))) * (2.0f * cell * cell);
    }
  }
  return sum;
}

TEST(EmissiveTexture, SamplesByLuminanceMatchTheBruteForceIrradiance) {
  const EmissionMap map = checkerMap();
  const Light light = makeMeshLight(kTriangles, Color(1.5f), 0, kUvs, &map);
  ASSERT_TRUE(light.emission);
  const Vec3 p(1.3f, 0.0f, 0.2f), n(0, 1, 0);
  const Color want = integrateQuad(map, 800, [&](Vec3 y, Color L) {
    const Vec3 d = y - p;
    const float d2 = glm::dot(d, d), c = d.y / std::sqrt(d2);  // cos at p and at the light
    return 1.5f * L * (c * c / d2);
  });
  const LightSampler s = prepareLight(light, p);
  Rng rng(5);
  Color sum(0.0f);
  const int count = 1 << 18;
  int onBlack = 0;
  for (int i = 0; i < count; ++i) {
    const LightIncidence in = sampleLight(s, rng.uniform(), rng.uniform());
    ASSERT_TRUE(in.valid);
    sum += in.radiance * glm::dot(in.wi, n);
    onBlack += maxComponent(map.at(Vec2(in.point.x / 2.0f, in.point.z))) < 0.05f;
  }
  // 2^18 samples: the estimate's standard error is below 0.3% here.
  for (int c = 0; c < 3; ++c) EXPECT_LT(rel(sum[c] / count, want[c]), 0.01) << "channel " << c;
  // The two triangles split the dark and bright texels unevenly; uniform area sampling
  // would put about a third of its samples on near-black texels.
  EXPECT_LT(double(onBlack) / count, 0.3);
}

TEST(EmissiveTexture, PhotonsCarryEachChannelsPower) {
  const EmissionMap map = checkerMap();
  const Light light = makeMeshLight(kTriangles, Color(1.5f), 0, kUvs, &map);
  const Color want = integrateQuad(map, 800, [](Vec3, Color L) { return kPi * 1.5f * L; });  // pi int L dA
  const Color power = lightPower(light, SceneSphere{});
  Rng rng(9);
  Color sum(0.0f);
  const int count = 1 << 18;
  for (int i = 0; i < count; ++i) {
    const PhotonRay r = sampleLightPhoton(light, SceneSphere{}, rng.uniform(), rng.uniform(), rng.uniform(),
                                          rng.uniform());
    ASSERT_LT(r.dir.y, 0.0f);  // one-sided: down only
    sum += r.weight;
  }
  for (int c = 0; c < 3; ++c) EXPECT_LT(rel(power[c] * sum[c] / count, want[c]), 0.01) << "channel " << c;
}

TEST(EmissiveTexture, TwoSidedMeshLightEmitsBothWaysWithTwicePower) {
  Light one = makeMeshLight(kTriangles, Color(2.0f), 0);
  Light two = one;
  two.twoSided = true;
  const Color p1 = lightPower(one, SceneSphere{}), p2 = lightPower(two, SceneSphere{});
  EXPECT_NEAR(p2.r, 2.0f * p1.r, 1e-5f * p2.r);
  // Mirror points below and above get the same irradiance; one-sided, nothing above.
  const Vec3 below(0.7f, 1.0f, 0.4f), above(0.7f, 3.0f, 0.4f);
  Color eBelow, eAbove, eOneAbove;
  ASSERT_TRUE(unoccludedIrradiance(prepareLight(two, below), Vec3(0, 1, 0), Vec3(0, 1, 0), eBelow));
  ASSERT_TRUE(unoccludedIrradiance(prepareLight(two, above), Vec3(0, -1, 0), Vec3(0, -1, 0), eAbove));
  ASSERT_TRUE(unoccludedIrradiance(prepareLight(one, above), Vec3(0, -1, 0), Vec3(0, -1, 0), eOneAbove));
  EXPECT_GT(eBelow.r, 0.1f);
  EXPECT_NEAR(eAbove.r, eBelow.r, 1e-5f * eBelow.r);
  EXPECT_EQ(eOneAbove.r, 0.0f);
  const LightSampler s = prepareLight(two, above);
  Rng rng(3);
  double sum = 0.0;
  const int count = 1 << 16;
  for (int i = 0; i < count; ++i) {
    const LightIncidence in = sampleLight(s, rng.uniform(), rng.uniform());
    ASSERT_TRUE(in.valid);
    sum += in.radiance.r * -in.wi.y;  // cos at the point, whose normal faces down
  }
  EXPECT_LT(rel(sum / count, eAbove.r), 0.01);
  int up = 0;
  for (int i = 0; i < count; ++i) {
    up += sampleLightPhoton(two, SceneSphere{}, rng.uniform(), rng.uniform(), rng.uniform(), rng.uniform()).dir.y > 0.0f;
  }
  EXPECT_NEAR(double(up) / count, 0.5, 0.01);
}

// A quad mesh of material 0 whose emission is `emission` x the EXR texture of
// `texels` (2 x 1); the loader's addMeshEmitters then decides what it becomes.
Scene texturedEmitter(const testing::ScratchDir& dir, Color left, Color right) {
  Image image(2, 1);
  image.at(0, 0) = left;
  image.at(1, 0) = right;
  const std::string file = (dir / "emission.exr").string();
  writeImage(file, image);
  Scene scene = physicalScene();
  scene.textures.push_back(Texture{file, false, std::nullopt});
  Material m = lambert("panel", Color(0.5f));
  m.emission = Color(3.0f);
  m.emissionTexture = 0;
  m.emitterShades = true;
  scene.materials.push_back(m);
  scene.meshes.push_back(makeQuad(Vec3(0, 2, 0), Vec3(0, 0, 1), Vec3(2, 0, 0), 0));  // uv over the quad
  addMeshEmitters(scene);
  return scene;
}

TEST(EmissiveTexture, MostlyDarkTextureGlowsWithoutBecomingALight) {
  testing::ScratchDir dir;
  // Mean luminance 0.01 over the mesh: below the decorative share, so no light.
  const Scene dark = texturedEmitter(dir, Color(0.0f), Color(0.02f));
  EXPECT_TRUE(dark.lights.empty());
  EXPECT_EQ(dark.materials[0].light, -1);
  ASSERT_EQ(dark.load.notes.size(), 1u);
  EXPECT_NE(dark.load.notes[0].find("lights nothing"), std::string::npos) << dark.load.notes[0];
  // Half bright: a light, textured, that keeps its reflecting surface.
  const Scene bright = texturedEmitter(dir, Color(0.0f), Color(1.0f));
  ASSERT_EQ(bright.lights.size(), 1u);
  EXPECT_TRUE(bright.lights[0].emission);
  EXPECT_EQ(bright.materials[0].light, 0);
  EXPECT_EQ(bright.materials[0].diffuse, Color(0.5f));
}

TEST(EmissiveTexture, AnEmitterThatReflectsAddsItsGlowToItsShading) {
  // A Lambert quad (rho 0.5) facing +z at z = 0 under a point light on the axis,
  // glowing 0.2 on its front: the camera sees 0.2 + rho / pi x E.
  Scene scene = physicalScene();
  Material m = lambert("panel", Color(0.5f));
  m.emission = Color(0.2f);
  m.emitterShades = true;
  scene.materials.push_back(m);
  scene.meshes.push_back(makeQuad(Vec3(-1, -1, 0), Vec3(2, 0, 0), Vec3(0, 2, 0), 0));
  Light point;
  point.position = Vec3(0.0f, 0.0f, 2.0f);
  point.intensity = 4.0f;
  scene.lights.push_back(point);
  addMeshEmitters(scene);
  ASSERT_EQ(scene.lights.size(), 2u);
  Rig rig(scene);
  const Color got = trace(rig, makeRay(Vec3(0, 0, 5), Vec3(0, 0, -1)), kTermAll);
  const double E = 4.0 / 4.0;  // I / d^2 at normal incidence
  EXPECT_NEAR(got.r, 0.2 + 0.5 / kPiD * E, 1e-3);
}

}  // namespace
}  // namespace penumbra
