// Media against analytic answers through the whole pipeline: the furnace (a medium
// that only scatters, in a uniform sky, shows the sky's radiance everywhere) and the
// volume caustic (a point light through glass into fog carries the energy of a small
// sphere light of equal power: the point light's cone comes from the volume map alone,
// the sphere light's by the same estimator, since glass blocks both lights' samples).
#include "plan/pipeline.h"
#include "core/color.h"
#include <gtest/gtest.h>
#include <cmath>
#include <filesystem>
#include <fstream>

namespace penumbra {
namespace {

namespace fs = std::filesystem;

RenderResult renderText(const std::string& name, const std::string& json) {
  const fs::path path = fs::temp_directory_path() / ("penumbra_test_media_" + name + ".json");
  std::ofstream(path) << json;
  RenderRequest r;
  r.scenePath = path.string();
  r.session.threads = 2;
  RenderResult out = runRender(r);
  fs::remove(path);
  return out;
}

// A sphere of radius 1 holding a medium of albedo 1 (an invisible boundary), seen from
// 4 units by a camera it fills, under a uniform sky of radiance 0.5: the radiative
// transfer equation's solution is 0.5 everywhere, whatever the optical depth. What a
// pixel holds beyond the sky seen through is single scattering (16 stratified light
// samples a stretch) and the volume map's multiple scattering, whose noise falls with
// photons gathered over the passes (k fixed: alpha 1, no kernel bias in a uniform field).
TEST(MediaPhysics, TheFurnaceReturnsTheSkyAtEveryPixel) {
  const std::string scene = R"({
  "camera": {"position": [0, 0, 4], "look_at": [0, 0, 0], "fov": 20, "width": 8, "height": 8, "spp": 16},
  "environment": {"color": [0.5, 0.5, 0.5]},
  "media": [{"name": "white", "sigma_a": 0, "sigma_s": 1, "g": 0.3}],
  "objects": [{"type": "sphere", "center": [0, 0, 0], "radius": 1, "medium": "white"}],
  "render": {"model": "physical", "max_depth": 10, "volume_samples": 16},
  "photons": {"gate": false, "global": 0, "caustic": 0, "volume": 1000000, "k_volume": 400, "passes": 20,
              "alpha": 1, "max_bounces": 64}})";
  const RenderResult r = renderText("furnace", scene);
  double worst = 0.0, mean = 0.0;
  for (const Color& c : r.image.pixels) {
    for (float v : {c.r, c.g, c.b}) {
      ASSERT_TRUE(std::isfinite(v));
      worst = std::max(worst, std::fabs(v / 0.5 - 1.0));
      mean += v / (0.5 * 3.0 * r.image.pixels.size());
    }
  }
  // Every pixel, corners grazing the sphere included, within 1% of the sky; the mean
  // within 0.2% (the beam's kernel reaching past the boundary reads a grazing ray low).
  EXPECT_NEAR(mean, 1.0, 0.002);
  EXPECT_LE(worst, 0.01) << "mean over the sky " << mean << ", relative noise " << r.stats.error.noiseRmse / 0.5;
}

// Fog (no absorption) around a glass sphere at height 1 with a light 1 unit above it;
// a black floor (nothing returns from it) and the camera looking at the cone below the
// sphere from the side. The cone's pixels (0.2 wide, from the floor to the sphere) sum
// the same light for a point light of intensity 1 (power 4 pi) and a sphere light of
// radius 0.01 and power 4 pi. Photons stop after 4 events for both lights alike (the
// cone's light is the first scatter after the glass's two refractions).
std::string causticScene(const std::string& light) {
  return R"({
  "camera": {"position": [0, 0.6, 3], "look_at": [0, 0.6, 0], "fov": 40, "width": 48, "height": 48, "spp": 1},
  "lights": [)" + light + R"(],
  "media": [{"name": "fog", "sigma_a": 0, "sigma_s": 0.2, "g": 0}],
  "materials": {"black": {"diffuse": 0}, "glass": {"diffuse": 0, "transparent": {"ior": 1.5}}},
  "objects": [{"type": "quad", "corner": [-5, 0, 5], "edge1": [10, 0, 0], "edge2": [0, 0, -10], "material": "black"},
              {"type": "sphere", "center": [0, 1, 0], "radius": 0.3, "material": "glass"}],
  "render": {"model": "physical", "max_depth": 10, "medium": "fog"},
  "photons": {"gate": false, "global": 0, "caustic": 200000, "volume": 2000000, "k_volume": 100, "passes": 4,
              "max_bounces": 4}})";
}

double coneEnergy(const Image& im) {
  // The plane z = 0 through the sphere's centre, projected by the pinhole camera.
  const double half = 3.0 * std::tan(20.0 * 3.14159265358979 / 180.0);
  auto px = [&](double x) { return int((x / half + 1.0) * 0.5 * im.width); };
  auto py = [&](double y) { return int((1.0 - (y - 0.6) / half) * 0.5 * im.height); };
  double sum = 0.0;
  for (int y = py(0.65); y < py(0.05); ++y)
    for (int x = px(-0.1); x < px(0.1); ++x) sum += meanOf(im.at(x, y));
  return sum;
}

TEST(MediaPhysics, TheVolumeCausticOfAPointLightMatchesASmallSphereLight) {
  const RenderResult point =
      renderText("caustic_point", causticScene(R"({"type": "point", "position": [0, 2, 0], "intensity": 1})"));
  const RenderResult sphere = renderText(
      "caustic_sphere",
      causticScene(R"({"type": "sphere", "center": [0, 2, 0], "radius": 0.01, "power": 12.566370614359172})"));
  const double a = coneEnergy(point.image), b = coneEnergy(sphere.image);
  ASSERT_GT(a, 0.0);  // the cone is lit: only the volume map can carry it from a point light
  EXPECT_NEAR(a / b, 1.0, 0.02) << "point " << a << ", sphere " << b;
}

}  // namespace
}  // namespace penumbra
