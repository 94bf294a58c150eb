// The scene file's media: every key parsed into Scene::media and the volume photon
// settings, overrides reaching them, and each bad value refused in one line.
#include "core/error.h"
#include "io/scene_loader.h"

#include "support/parse_error.h"
#include <gtest/gtest.h>

using namespace penumbra;

namespace {

// A physical scene with `media` (a JSON array), extra objects and extra render keys.
std::string scene(const std::string& media, const std::string& objects = "", const std::string& render = "",
                  const std::string& model = "physical") {
  return R"({"camera": {"position": [0, 0, 5]}, "lights": [{"type": "point", "position": [0, 3, 0]}],
             "materials": {"m": {"diffuse": 0.5}}, "media": )" + media +
         R"(, "objects": [{"type": "sphere", "center": [0, 0, -3], "radius": 0.5, "material": "m"})" +
         (objects.empty() ? "" : ", " + objects) + R"(], "render": {"model": ")" + model + "\"" +
         (render.empty() ? "" : ", " + render) + "}}";
}

using penumbra::testing::errorOf;

const std::string kFog = R"([{"name": "fog", "sigma_a": 0.01, "sigma_s": [0.1, 0.2, 0.3], "g": 0.3,
                              "emission": [0.5, 0, 0]}])";

TEST(IoMedia, EveryKeyParses) {
  const Scene s = parseScene(scene(kFog, "", R"("medium": "fog")"), "x.json");
  ASSERT_EQ(s.media.size(), 1u);
  const Medium& m = s.media[0];
  EXPECT_EQ(m.name, "fog");
  EXPECT_EQ(m.sigmaA, Color(0.01f));
  EXPECT_EQ(m.sigmaS, Color(0.1f, 0.2f, 0.3f));
  EXPECT_FLOAT_EQ(m.g, 0.3f);
  EXPECT_EQ(m.emission, Color(0.5f, 0.0f, 0.0f));
  EXPECT_TRUE(m.homogeneous());
  EXPECT_EQ(s.sceneMedium, 0);
  EXPECT_EQ(s.cameraMedium, 0);  // nothing closed around the camera: the scene's fog
}

TEST(IoMedia, DefaultsAreAVacuumLikeMediumAndNoSceneMedium) {
  const Scene s = parseScene(scene(R"([{"name": "m"}])"), "x.json");
  EXPECT_EQ(s.media[0].sigmaT(), Color(0.0f));
  EXPECT_EQ(s.media[0].g, 0.0f);
  EXPECT_EQ(s.sceneMedium, kNoMedium);
  EXPECT_EQ(s.cameraMedium, kNoMedium);
}

TEST(IoMedia, EnvironmentMediumFillsTheSceneToo) {
  std::string json = scene(kFog);
  json.insert(json.rfind('}'), R"(, "environment": {"color": 0.2, "medium": "fog"})");
  const Scene s = parseScene(json, "x.json");
  EXPECT_EQ(s.sceneMedium, 0);
  EXPECT_EQ(s.lights.back().medium, 0);  // the environment's photons start in it
}

TEST(IoMedia, ExtremeButValidValuesLoad) {
  EXPECT_EQ(errorOf(scene(R"([{"name": "a", "sigma_s": 1e30, "g": 0.999999}])")), "");
  EXPECT_EQ(errorOf(scene(R"([{"name": "a", "sigma_a": 0, "sigma_s": 0, "g": -0.999999}])")), "");
}

TEST(IoMedia, VolumePhotonSettings) {
  std::string json = scene(kFog);
  json.insert(json.rfind('}'), R"(, "photons": {"volume": 12345, "k_volume": 77, "volume_radius": 0.25})");
  const Scene s = parseScene(json, "x.json");
  EXPECT_EQ(s.photons.volumePhotons, 12345u);
  EXPECT_EQ(s.photons.kVolume, 77);
  EXPECT_FLOAT_EQ(s.photons.volumeRadius, 0.25f);
}

TEST(IoMedia, OverridesReachMediaKeys) {
  const Scene s = parseScene(scene(kFog), "x.json", {"media[0].sigma_s=[1,2,3]", "media[0].g=-0.5"});
  EXPECT_EQ(s.media[0].sigmaS, Color(1.0f, 2.0f, 3.0f));
  EXPECT_FLOAT_EQ(s.media[0].g, -0.5f);
  const std::string e = errorOf(scene(kFog), {"media[0].g=1"});
  EXPECT_NE(e.find("media[0].g"), std::string::npos) << e;
  EXPECT_NE(e.find("--set"), std::string::npos) << e;
}

TEST(IoMedia, BoundaryObjectsLeaveTheSurfaceLists) {
  const Scene s = parseScene(scene(kFog, R"({"type": "sphere", "center": [0, 0, 0], "radius": 1, "medium": "fog"},
      {"type": "box", "min": [2, 0, 0], "max": [3, 1, 1], "medium": "fog"},
      {"type": "box", "min": [-3, 0, 0], "max": [-2, 1, 1], "medium": "fog", "material": "m"})"), "x.json");
  EXPECT_EQ(s.spheres.size(), 1u);
  EXPECT_EQ(s.boundarySpheres.size(), 1u);
  EXPECT_EQ(s.boundaryMeshes.size(), 1u);
  ASSERT_EQ(s.meshes.size(), 1u);  // the box with a material is a visible surface
  EXPECT_EQ(s.meshes[0].media.inside, 0);
  EXPECT_TRUE(s.meshes[0].media.separates);
  EXPECT_EQ(s.boundarySpheres[0].media.inside, 0);
}

// Each refusal: one line, naming the file and the JSON path, saying the problem.
void expectRefused(const std::string& json, const std::string& path, const std::string& problem,
                   const std::vector<std::string>& overrides = {}) {
  const std::string e = errorOf(json, overrides);
  EXPECT_EQ(e.find('\n'), std::string::npos) << e;
  EXPECT_EQ(e.rfind("x.json: ", 0), 0u) << e;
  EXPECT_NE(e.find(path), std::string::npos) << "path " << path << " in: " << e;
  EXPECT_NE(e.find(problem), std::string::npos) << "problem " << problem << " in: " << e;
}

TEST(IoMedia, BadValuesAreRefusedInOneLine) {
  expectRefused(scene(R"([{"name": "a", "sigma_s": -1}])"), "media[0].sigma_s", "must be between 0 and 1e+30");
  expectRefused(scene(R"([{"name": "a", "sigma_a": [0, -0.5, 0]}])"), "media[0].sigma_a[1]", "must be between 0 and 1e+30");
  expectRefused(scene(R"([{"name": "a", "sigma_s": 1e39}])"), "media[0].sigma_s", "must be between 0 and 1e+30");
  expectRefused(scene(R"([{"name": "a", "sigma_s": [1, 2]}])"), "media[0].sigma_s", "[r, g, b]");
  expectRefused(scene(R"([{"name": "a", "g": 1}])"), "media[0].g", "");
  expectRefused(scene(R"([{"name": "a", "g": -1}])"), "media[0].g", "");
  expectRefused(scene(R"([{"name": "a", "emission": -2}])"), "media[0].emission", ">= 0");
  expectRefused(scene(R"([{"name": "a", "sigma": 1}])"), "media[0]", "sigma");
  expectRefused(scene(R"([{"sigma_s": 1}])"), "media[0]", "name");
  expectRefused(scene(R"([{"name": "a"}, {"name": "a"}])"), "media[1].name", "duplicate medium name \"a\"");
  expectRefused(scene(R"({"name": "a"})"), "media", "array");
}

TEST(IoMedia, UnknownNamesSuggestTheClosest) {
  expectRefused(scene(kFog, "", R"("medium": "fgo")"), "render.medium", "unknown medium \"fgo\" (did you mean \"fog\"?)");
  expectRefused(scene(kFog, R"({"type": "box", "min": [0, 0, 0], "max": [1, 1, 1], "medium": "smoke"})"),
                "objects[1].medium", "unknown medium \"smoke\"");
  expectRefused(scene("[]", "", R"("medium": "fog")"), "render.medium", "the scene has no \"media\"");
}

TEST(IoMedia, TheClassicModelRefusesMediaNamingThem) {
  expectRefused(scene(kFog, "", "", "classic"), "media[0]", "media need the physical model");
  expectRefused(scene(kFog, "", "", "classic"), "media[0]", "\"fog\"");
  EXPECT_EQ(errorOf(scene("[]", "", "", "classic")), "");  // an empty list is no medium
}

TEST(IoMedia, AMediumNeedsAClosedObject) {
  expectRefused(scene(kFog, R"({"type": "quad", "corner": [0, 0, 0], "edge1": [1, 0, 0], "edge2": [0, 1, 0],
                                "medium": "fog"})"),
                "objects[1].medium", "open");
  expectRefused(scene(kFog, R"({"type": "teapot", "subdivisions": 2, "medium": "fog", "material": "m"})"),
                "objects[1].medium", "a medium fills a closed object");
}

TEST(IoMedia, TheSceneMediumIsGivenOnce) {
  std::string json = scene(kFog, "", R"("medium": "fog")");
  json.insert(json.rfind('}'), R"(, "environment": {"medium": "fog"})");
  expectRefused(json, "environment.medium", "given twice");
}

}  // namespace
