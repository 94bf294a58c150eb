// Vertex colours against closed forms: a point light over a Lambert plane whose
// colour varies across it (physical rho/pi I cos / d^2 and the classic k_d I cos / d^2,
// each times the colour), a metallic-roughness base tinted by a colour as by the same
// base colour, and photons bouncing off a coloured floor carrying its colour into the
// global and indirect maps. The vertex alpha's cut-outs: test_physical_alpha_mask.
#include "support/physical_fixtures.h"
#include "support/emit_fixtures.h"

namespace penumbra {
namespace {

const Vec3 kLight(0.3f, 1.5f, -0.2f);
constexpr float kIntensity = 2.0f;
constexpr float kRho = 0.5f;

// An affine colour over the plane: barycentric interpolation reproduces it exactly
// on every triangle, so the expected colour at a hit is this function of its point.
Color colourAt(const glm::dvec3& p) {
  return Color(float(0.6 + 0.006 * p.x), float(0.5 + 0.004 * p.z), float(0.3 + 0.002 * (p.x - p.z)));
}

// The 100 x 100 plane y = 0 with colourAt at its corners, under the point light.
Scene colouredPlane(ShadingModel model) {
  Scene scene = physicalScene();
  scene.render.model = model;
  scene.render.ambient = Color(0.2f);
  Material plane = lambert("plane", Color(kRho));
  plane.ambient = Color(0.1f);
  scene.materials.push_back(plane);
  TriangleMesh quad = makeQuad(Vec3(-50, 0, -50), Vec3(0, 0, 100), Vec3(100, 0, 0), 0);
  for (const Vec3& p : quad.positions) quad.colors.emplace_back(colourAt(glm::dvec3(p)), 1.0f);
  scene.meshes.push_back(quad);
  scene.lights.push_back(point(kLight, Color(1.0f), kIntensity));
  scene.camera = axisCamera(Vec3(0.0f, 4.0f, 3.0f), Vec3(0.0f));
  return scene;
}

// Every pixel of the rendered image against c(p) x (the model's closed form at p),
// p where the pixel's ray meets y = 0 (in double). Tolerance 1e-4 relative: nothing
// is sampled, only float rounding.
void expectPlaneImage(ShadingModel model) {
  const Scene scene = colouredPlane(model);
  Rig rig(scene);
  const Image img = rig.render();
  CameraRays cam(scene.camera);
  for (int y = 0; y < img.height; ++y) {
    for (int x = 0; x < img.width; ++x) {
      const Ray ray = cam.generate(x + 0.5f, y + 0.5f);
      const glm::dvec3 o(ray.origin), d(ray.dir);
      const glm::dvec3 p = o - (o.y / d.y) * d;
      const glm::dvec3 toLight = glm::dvec3(kLight) - p;
      const double d2 = glm::dot(toLight, toLight), cosT = toLight.y / std::sqrt(d2);
      const double irradiance = kIntensity * cosT / d2;
      const double shade = model == ShadingModel::Physical ? kRho / kPiD * irradiance : 0.1 * 0.2 + kRho * irradiance;
      const Color c = colourAt(p);
      for (int k = 0; k < 3; ++k) {
        ASSERT_LT(rel(img.at(x, y)[k], c[k] * shade), 1e-4) << "pixel " << x << "," << y << " channel " << k;
      }
    }
  }
}

TEST(VertexColors, PhysicalLambertPlaneIsColourTimesRhoOverPiICosOverD2) { expectPlaneImage(ShadingModel::Physical); }

TEST(VertexColors, ClassicDiffuseAndAmbientTermsAreTimesTheColour) { expectPlaneImage(ShadingModel::Classic); }

TEST(VertexColors, MetallicRoughnessBaseTimesColourEqualsThatBaseColour) {
  // A glTF-style material (metallic 0.3, roughness 0.5) with vertex colour c renders
  // as the same material with base colour base x c, in both models (the metal's
  // highlight takes the colour too). Tolerance 1e-5 relative: the interpolated
  // colour is c within float rounding.
  const Color base(0.8f, 0.7f, 0.6f), c(0.9f, 0.5f, 0.2f);
  for (ShadingModel model : {ShadingModel::Physical, ShadingModel::Classic}) {
    Scene tinted = colouredPlane(model);
    Material& m = tinted.materials[0];
    m.metalRough = true;
    m.metallic = 0.3f;
    m.roughness = 0.5f;
    m.diffuse = base;
    Scene plain = tinted;
    tinted.meshes[0].colors.assign(4, glm::vec4(c, 1.0f));
    plain.meshes[0].colors.clear();
    plain.materials[0].diffuse = base * c;
    plain.materials[0].ambient = tinted.materials[0].ambient * c;
    Rig a(tinted), b(plain);
    const Image ia = a.render(), ib = b.render();
    for (size_t i = 0; i < ia.pixels.size(); ++i) {
      for (int k = 0; k < 3; ++k) {
        ASSERT_NEAR(ia.pixels[i][k], ib.pixels[i][k], 1e-5f * ib.pixels[i][k] + 1e-9f)
            << (model == ShadingModel::Physical ? "physical" : "classic") << " pixel " << i << " channel " << k;
      }
    }
  }
}

// ---------------------------------------------------------------------------
// Photons bouncing off a coloured floor.

// A spot at y = 1.9 shining down (its cone meets only the floor), a floor at y = 0
// of vertex colour `c`, a white ceiling at y = 2: every photon meets the floor first,
// so whatever reaches the ceiling has bounced off the colour.
Scene bounceScene(ShadingModel model, const Color& c) {
  Scene scene = physicalScene();
  scene.render.model = model;
  Material floor = lambert("floor", Color(kRho)), ceiling = lambert("ceiling", Color(kRho));
  floor.pR = ceiling.pR = 0.6f;  // the classic roulette's reflection
  scene.materials = {floor, ceiling};
  TriangleMesh bottom = makeQuad(Vec3(-20, 0, -20), Vec3(0, 0, 40), Vec3(40, 0, 0), 0);
  bottom.colors.assign(4, glm::vec4(c, 1.0f));
  scene.meshes.push_back(bottom);
  scene.meshes.push_back(makeQuad(Vec3(-20, 2, -20), Vec3(40, 0, 0), Vec3(0, 0, 40), 1));
  Light spot = point(Vec3(0.0f, 1.9f, 0.0f), Color(1.0f), 10.0f);
  spot.direction = Vec3(0, -1, 0);
  setSpotCone(spot, 0.3f, 0.5f);
  scene.lights.push_back(spot);
  scene.photons.maxBounces = 1;  // floor, then the ceiling: one diffuse bounce
  return scene;
}

TEST(VertexColors, GlobalPhotonsOffARedFloorAreRedAndKeepTheColoursRatios) {
  // Physical global map: stored after one diffuse bounce, which is off the floor.
  // Red: every stored photon has exactly zero green and blue. c = (1, 0.5, 0.25): the
  // stored power's channels stand as c (the tally sums unpacked floats; 1e-5).
  Scene red = bounceScene(ShadingModel::Physical, Color(1, 0, 0));
  red.photons.globalPhotons = 20000;
  TraceScene tracer(red);
  const EmittedPhotons photons = emitPhysicalPhotons(red, tracer, 0, sceneEmit(red));
  size_t stored = 0;
  for (const IndirectPhoton& p : photons.batches.get<MapKind::Global>()) {
    const Color power = p.power.color();
    EXPECT_GT(p.position.y, 1.99f);
    ASSERT_EQ(power.g, 0.0f);
    ASSERT_EQ(power.b, 0.0f);
    ASSERT_GT(power.r, 0.0f);
    ++stored;
  }
  EXPECT_GT(stored, 2000u);

  Scene tinted = bounceScene(ShadingModel::Physical, Color(1.0f, 0.5f, 0.25f));
  tinted.photons.globalPhotons = 20000;
  TraceScene tinter(tinted);
  const glm::dvec3 sum = emitPhysicalPhotons(tinted, tinter, 0, sceneEmit(tinted)).tally[MapKind::Global].stored[MapKind::Global];
  ASSERT_GT(sum.r, 0.0);
  EXPECT_NEAR(sum.g / sum.r, 0.5, 1e-5);
  EXPECT_NEAR(sum.b / sum.r, 0.25, 1e-5);
}

TEST(VertexColors, ClassicIndirectPhotonsOffTheFloorTakeItsHue) {
  // The classic roulette's survivor takes the surface's hue (colour / its largest
  // channel): on the ceiling, c = (1, 0.5, 0.25) in every photon, within the packed
  // power's 2^-8 of the largest channel; red leaves zero green and blue.
  for (const Color& c : {Color(1, 0, 0), Color(1.0f, 0.5f, 0.25f)}) {
    const Scene scene = bounceScene(ShadingModel::Classic, c);
    TraceScene tracer(scene);
    EmitOptions options;
    options.budgets[MapKind::Indirect] = 20000;
    const EmittedPhotons maps = emitPhotons(scene, tracer, options);
    size_t onCeiling = 0;
    for (const IndirectPhoton& p : maps.batches.get<MapKind::Indirect>()) {
      if (p.position.y < 1.0f) continue;
      const Color power = p.power.color();
      ASSERT_GT(power.r, 0.0f);
      ASSERT_NEAR(power.g, c.g * power.r, power.r / 256.0f);
      ASSERT_NEAR(power.b, c.b * power.r, power.r / 256.0f);
      if (c.g == 0.0f) {
        ASSERT_EQ(power.g + power.b, 0.0f);
      }
      ++onCeiling;
    }
    EXPECT_GT(onCeiling, 2000u);
  }
}

}  // namespace
}  // namespace penumbra
