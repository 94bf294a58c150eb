// Emissive triangle meshes as area lights (LightType::Mesh): a quad of two emitting
// triangles against the equivalent quad light and the analytic form factor, its
// power pi A L, photons from uniform points in cosine directions, and its surface
// seen by camera rays on the emitting side only.
#include "support/form_factor.h"
#include "core/light_sample.h"
#include "core/lights/emissive_mesh.h"
#include "io/scene_sections.h"
#include "support/physical_fixtures.h"

namespace penumbra {
namespace {

using testing::rectFactor;

constexpr float kA = 1.0f, kB = 0.8f, kH = 1.2f, kL = 3.0f;
const Color kColour(1.0f, 0.9f, 0.7f);
const Vec3 kCorner(-kA / 2, kH, -kB / 2), kE1(kA, 0, 0), kE2(0, 0, kB);  // e1 x e2 = -y: faces down

// A Lambert plane (rho 0.5) under either a quad light or an emissive two-triangle mesh.
Scene planeUnder(bool meshEmitter) {
  Scene scene = physicalScene();
  scene.materials.push_back(lambert("plane", Color(0.5f)));
  scene.meshes.push_back(makeQuad(Vec3(-50, 0, -50), Vec3(0, 0, 100), Vec3(100, 0, 0), 0));
  scene.render.lightSamples = 1024;
  if (meshEmitter) {
    Material glow = lambert("glow", Color(0.7f));
    glow.emission = kColour * kL;
    scene.materials.push_back(glow);
    scene.meshes.push_back(makeQuad(kCorner, kE1, kE2, 1));
  } else {
    scene.lights.push_back(quadLight(kCorner, kE1, kE2, kColour, kL));
  }
  addEmitters(scene);
  addMeshEmitters(scene);
  return scene;
}

TEST(MeshLight, EmissiveMaterialBecomesOneMeshLightWithPowerPiAL) {
  const Scene scene = planeUnder(true);
  ASSERT_EQ(scene.lights.size(), 1u);
  const Light& light = scene.lights[0];
  EXPECT_EQ(light.type, LightType::Mesh);
  EXPECT_EQ(light.triangles.size(), 6u);
  EXPECT_NEAR(lightArea(light), kA * kB, 1e-6);
  EXPECT_FALSE(isDeltaLight(light));
  EXPECT_EQ(lightSampleCount(light, 16), 16);
  const Color power = lightPower(light, SceneSphere{});
  for (int c = 0; c < 3; ++c) EXPECT_NEAR(power[c], kPiD * kA * kB * kL * kColour[c], 1e-4 * power[c]);
  // Its surface only glows now, like a quad light's, and names its light.
  const Material& glow = scene.materials[1];
  EXPECT_EQ(glow.light, 0);
  EXPECT_EQ(maxComponent(glow.diffuse), 0.0f);
}

TEST(MeshLight, IrradianceMatchesTheQuadLightAndTheFormFactor) {
  const Scene mesh = planeUnder(true), quad = planeUnder(false);
  Rig meshRig(mesh), quadRig(quad);
  const Vec3 eye(-2.0f, 0.9f, 1.5f), n(0, 1, 0);
  for (Vec3 p : {Vec3(0.0f), Vec3(0.3f, 0.0f, 0.2f), Vec3(1.1f, 0.0f, -0.6f), Vec3(-2.5f, 0.0f, 0.4f)}) {
    const double F = rectFactor(kCorner.x - p.x, kCorner.x + kA - p.x, kCorner.z - p.z, kCorner.z + kB - p.z, kH);
    // Sampled (1024 stratified samples by area, a shadow ray each: the gate is off).
    const Color gotMesh = trace(meshRig, makeRay(eye, p - eye), kTermDirect);
    const Color gotQuad = trace(quadRig, makeRay(eye, p - eye), kTermDirect);
    // Closed form: Lambert's formula over the two triangles against the quad's.
    Color eMesh, eQuad;
    ASSERT_TRUE(unoccludedIrradiance(prepareLight(mesh.lights[0], p), n, n, eMesh));
    ASSERT_TRUE(unoccludedIrradiance(prepareLight(quad.lights[0], p), n, n, eQuad));
    for (int c = 0; c < 3; ++c) {
      const double want = 0.5 * kL * kColour[c] * F;  // rho L F
      EXPECT_LT(rel(gotMesh[c], want), 0.01) << "p = " << p.x << "," << p.z << " channel " << c;
      EXPECT_LT(rel(gotMesh[c], gotQuad[c]), 0.01);
      EXPECT_LT(rel(eMesh[c], kPiD * kL * kColour[c] * F), 1e-3);
      EXPECT_LT(rel(eMesh[c], eQuad[c]), 1e-4);
    }
  }
}

TEST(MeshLight, SamplesAreUniformByAreaWithTheRightPdf) {
  // Two triangles of areas 1 and 3 in the plane y = 2, facing down: a point below
  // gets each sample's L cos A / d^2, and averaging those is the irradiance.
  const std::vector<Vec3> tris = {Vec3(0, 2, 0), Vec3(2, 2, 0), Vec3(0, 2, 1),
                                  Vec3(2, 2, 0), Vec3(4, 2, 0), Vec3(2, 2, 3)};
  const Light light = makeMeshLight(tris, Color(2.0f), 0);
  ASSERT_NEAR(meshLightArea(light), 4.0f, 1e-6);
  const Vec3 p(1.5f, 0.0f, 0.5f), n(0, 1, 0);
  const LightSampler s = prepareLight(light, p);
  Rng rng(7);
  double sum = 0.0, inFirst = 0.0;
  const int count = 1 << 16;
  for (int i = 0; i < count; ++i) {
    const LightIncidence in = sampleLight(s, rng.uniform(), rng.uniform());
    ASSERT_TRUE(in.valid);
    ASSERT_NEAR(in.point.y, 2.0f, 1e-5);
    if (in.point.x < 2.0f && in.point.z < 1.0f - 0.5f * in.point.x) inFirst += 1.0;
    sum += in.radiance.r * glm::dot(in.wi, n);
  }
  Color E;
  ASSERT_TRUE(unoccludedIrradiance(s, n, n, E));
  EXPECT_LT(rel(sum / count, E.r), 0.01);
  EXPECT_NEAR(inFirst / count, 0.25, 0.01);  // area 1 of 4
}

TEST(MeshLight, PhotonsLeaveUniformPointsInCosineDirections) {
  const Scene scene = planeUnder(true);
  const Light& light = scene.lights[0];
  Rng rng(11);
  double cosSum = 0.0, xSum = 0.0;
  const int count = 1 << 16;
  for (int i = 0; i < count; ++i) {
    const PhotonRay r = sampleLightPhoton(light, SceneSphere{}, rng.uniform(), rng.uniform(), rng.uniform(),
                                          rng.uniform());
    ASSERT_NEAR(r.origin.y, kH, 1e-5);
    ASSERT_GE(r.origin.x, kCorner.x - 1e-5f);
    ASSERT_LE(r.origin.x, kCorner.x + kA + 1e-5f);
    ASSERT_NEAR(r.normal.y, -1.0f, 1e-6);
    const float c = -r.dir.y;
    ASSERT_GT(c, 0.0f);
    cosSum += c;
    xSum += r.origin.x;
  }
  EXPECT_NEAR(cosSum / count, 2.0 / 3.0, 0.005);  // E[cos] of a cosine-weighted lobe
  EXPECT_NEAR(xSum / count, 0.0, 0.005);          // uniform over the quad: its centre
}

TEST(MeshLight, CameraSeesTheRadianceOnTheEmittingSideOnly) {
  const Scene scene = planeUnder(true);
  Rig rig(scene);
  const Color below = trace(rig, makeRay(Vec3(0.1f, 0.5f, 0.1f), Vec3(0, 1, 0)), kTermDirect | kTermEmitters);
  expectColorNear(below, kColour * kL, 1e-5f, "from below");
  const Color above = trace(rig, makeRay(Vec3(0.1f, 3.0f, 0.1f), Vec3(0, -1, 0)), kTermDirect | kTermEmitters);
  EXPECT_EQ(maxComponent(above), 0.0f) << "its back is black, and it shadows the plane";
}

}  // namespace
}  // namespace penumbra
