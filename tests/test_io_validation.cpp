// Float validation: every value the loader accepts is usable in single
// precision, including what the renderer derives from it (camera basis, sphere
// normals, radiance, light power and their sum); each refused class fails with
// one line naming the file, the JSON path and the problem.
#include "core/error.h"
#include "core/light_sample.h"
#include "io/float_checks.h"
#include "io/scene_loader.h"

#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <string>
#include <vector>

using namespace penumbra;

namespace {

const std::string kCamera = R"({"position": [0, 0, 5], "look_at": [0, 0, 0]})";
const std::string kPointLight = R"([{"type": "point", "position": [2, 4, 3], "intensity": 10}])";
const std::string kMaterials =
    R"({"grey": {"diffuse": 0.5}, "glass": {"transparent": {"ior": 1.5}}})";
const std::string kSphere = R"([{"type": "sphere", "center": [0, 0, 0], "radius": 1, "material": "grey"}])";

std::string sceneText(const std::string& objects = kSphere, const std::string& lights = kPointLight,
                      const std::string& camera = kCamera, const std::string& materials = kMaterials) {
  return R"({"camera": )" + camera + R"(, "lights": )" + lights + R"(, "materials": )" + materials +
         R"(, "objects": )" + objects + "}";
}

std::string errorOf(const std::string& json, const std::vector<std::string>& overrides = {}) {
  try {
    parseScene(json, "v.json", overrides);
  } catch (const InputError& e) {
    return e.what();
  }
  return "";
}

// A number as JSON text with enough digits to round-trip a float bound.
std::string num(double v) {
  char buf[32];
  std::snprintf(buf, sizeof buf, "%.9g", v);
  return buf;
}

// The message is one line "v.json: PATH: ..." and contains `problem`.
void expectRefused(const std::string& json, const std::string& path, const std::string& problem,
                   const std::vector<std::string>& overrides = {}) {
  const std::string message = errorOf(json, overrides);
  ASSERT_FALSE(message.empty()) << "loaded: " << json;
  EXPECT_EQ(message.rfind("v.json: " + path + ": ", 0), 0u) << message;
  EXPECT_NE(message.find(problem), std::string::npos) << message;
  EXPECT_EQ(message.find('\n'), std::string::npos) << message;
}

}  // namespace

TEST(FloatValidation, ValuesThatRoundToZeroFailTheirFloatRange) {
  // 1e-50 > 0 in double, but the renderer would get 0.0f.
  expectRefused(sceneText(R"([{"type": "sphere", "center": [0, 0, 0], "radius": 1e-50, "material": "grey"}])"),
                "objects[0].radius", "must be > 0, got 1e-50 (0 in single precision)");
  expectRefused(sceneText(), "camera.fov", "(0 in single precision)", {"camera.fov=1e-50"});
  // Closed bounds are compared after rounding too, so a bound itself still loads.
  EXPECT_EQ(errorOf(sceneText(), {"photons.lookup_cell=0.05", "render.min_weight=1"}), "");
}

TEST(FloatValidation, IorOutsideItsRangeIsRefusedAndItsBoundsLoad) {
  expectRefused(sceneText(), "materials.glass.transparent.ior", "must be between 0.01 and 100, got 1e+30",
                {"materials.glass.transparent.ior=1e30"});
  expectRefused(sceneText(), "materials.glass.transparent.ior", "must be between 0.01 and 100",
                {"materials.glass.transparent.ior=1e-50"});
  for (double ior : {kMinIor, 0.5, 1.0, kMaxIor}) {
    Scene s = parseScene(sceneText(), "v.json", {"materials.glass.transparent.ior=" + num(ior)});
    EXPECT_FLOAT_EQ(s.materials[0].ior, static_cast<float>(ior));  // "glass" sorts first
  }
}

TEST(FloatValidation, CameraBasisIsCheckedInFloat) {
  // Lengths of 1e-30 are fine in double; squared in float they underflow to 0.
  expectRefused(sceneText(), "camera.up", "up has no direction in single precision",
                {"camera.up=[1e-30, 1e-30, 0]"});
  expectRefused(sceneText(kSphere, kPointLight, R"({"position": [0, 0, 1e-30], "look_at": [0, 0, 0]})"),
                "camera.look_at", "look_at equals position, or is too close");
  expectRefused(sceneText(), "camera.up", "up has no direction", {"camera.up=[0, 1e30, 0]"});
  // Short but representable: loads.
  Scene s = parseScene(sceneText(), "v.json", {"camera.up=[0, 1e-15, 0]"});
  EXPECT_FLOAT_EQ(s.camera.up.y, 1e-15f);
}

TEST(FloatValidation, PositionsBeyondTheCoordinateLimitAreRefused) {
  // Embree asserts on ray origins beyond ~1.8e18; geometry that far was invisible.
  expectRefused(sceneText(), "camera.position", "within +-1e+15", {"camera.position=[0, 0, 2e18]"});
  expectRefused(sceneText(), "lights[0].position", "within +-1e+15", {"lights[0].position=[2e18, 0, 0]"});
  expectRefused(sceneText(), "objects[0].center", "within +-1e+15", {"objects[0].center=[0, 2e15, 0]"});
  expectRefused(sceneText(), "objects[0].radius", "center +- radius must be within",
                {"objects[0].radius=2e15"});
  expectRefused(sceneText(R"([{"type": "box", "min": [0, 0, 0], "max": [1, 1, 1], "material": "grey",
                               "translate": [0, 0, -2e15]}])"),
                "objects[0]", "transformed positions must be within +-1e+15");
  expectRefused(sceneText(kSphere, R"([{"type": "quad", "corner": [0, 3, 0], "edge1": [1, 0, 0],
                                        "edge2": [0, 0, 2e15]}])"),
                "lights[0].edge2", "the quad's corners must be within");
  // At the limit: loads (without spheres, which would be too small against 1e15).
  Scene s = parseScene(sceneText("[]", R"([{"type": "point", "position": [1e15, 0, 0]}])",
                                 R"({"position": [0, 0, -1e15], "look_at": [0, 0, 0]})"),
                       "v.json");
  EXPECT_FLOAT_EQ(s.lights[0].position.x, 1e15f);
  EXPECT_FLOAT_EQ(s.camera.position.z, -1e15f);
}

TEST(FloatValidation, SphereRadiusMustBeResolvableAgainstItsCentre) {
  // The sphere sits at the origin: any positive float radius is representable there.
  Scene tiny = parseScene(sceneText(), "v.json", {"objects[0].radius=1e-9"});
  EXPECT_EQ(tiny.spheres[0].radius, 1e-9f);
  // Moved to x = 4, its radius must be >= 4 / 2^18.
  const double least = kMinRadiusRatio * 4.0;
  expectRefused(sceneText(), "objects[0].radius", "2^-18 x its centre's largest coordinate",
                {"objects[0].center=[4,0,0]", "objects[0].radius=1e-9"});
  expectRefused(sceneText(), "objects[0].radius", "could not be told from its centre",
                {"objects[0].center=[4,0,0]", "objects[0].radius=" + num(least * 0.99)});
  Scene s = parseScene(sceneText(), "v.json", {"objects[0].center=[4,0,0]", "objects[0].radius=" + num(least * 1.01)});
  EXPECT_GE(s.spheres[0].radius, static_cast<float>(least));
  // Sphere lights are spheres in the scene too.
  expectRefused(sceneText(kSphere, R"([{"type": "sphere", "center": [0, 3, 0], "radius": 1e-9}])"),
                "lights[0].radius", "2^-18 x its centre's largest coordinate");
}

TEST(FloatValidation, LightRadianceIsBoundedAsAProductInFloat) {
  // 3e38 is a valid float but no colour may exceed 1e30.
  expectRefused(sceneText(), "lights[0].color", "must be <= 1e+30", {"lights[0].color=3e38"});
  // Each factor is fine; their float product is +inf.
  expectRefused(sceneText(), "lights[0].intensity", "color x intensity = inf exceeds 1e+30",
                {"lights[0].color=1e20", "lights[0].intensity=1e20"});
  expectRefused(sceneText(kSphere, R"([{"type": "quad", "corner": [0, 3, 0], "edge1": [1, 0, 0],
                                        "edge2": [0, 0, 1], "radiance": 1e30, "color": 2}])"),
                "lights[0].radiance", "color x radiance = 2e+30 exceeds 1e+30");
  // power / (pi A) on a tiny area: the radiance it implies is what must fit.
  expectRefused(sceneText(kSphere, R"([{"type": "quad", "corner": [0, 3, 0], "edge1": [1e-5, 0, 0],
                                        "edge2": [0, 0, 1e-5], "power": 1e25}])"),
                "lights[0].power", "color x radiance");
}

TEST(FloatValidation, LightPowerIsBoundedForEveryLightType) {
  // 4 pi I for a point light.
  expectRefused(sceneText(), "lights[0].intensity", "light power 4 pi x color x intensity = 1.26e+30",
                {"lights[0].intensity=1e29"});
  // pi A L for an area light: A = 1e6, L = 1e25.
  expectRefused(sceneText(kSphere, R"([{"type": "quad", "corner": [-500, 3, -500], "edge1": [1000, 0, 0],
                                        "edge2": [0, 0, 1000], "radiance": 1e25}])"),
                "lights[0].radiance", "light power pi x area x color x radiance");
  // E pi R^2 for a directional light over the geometry's bounding disc (R ~ 1.7e3, pi R^2 ~ 9.4e6).
  expectRefused(sceneText(R"([{"type": "box", "min": [-1000, -1000, -1000], "max": [1000, 1000, 1000],
                               "material": "grey"}])",
                          R"([{"type": "directional", "direction": [0, -1, 0], "intensity": 1e24}])"),
                "lights[0].intensity", "over the scene's bounding disc");
}

TEST(FloatValidation, TotalLightPowerIsBoundedAndTheBoundLoads) {
  // Each light's 4 pi I = 6.3e29 fits; their sum 1.26e30 does not.
  const std::string two = R"([{"type": "point", "position": [2, 4, 3], "intensity": 5e28},
                               {"type": "point", "position": [-2, 4, 3], "intensity": 5e28}])";
  expectRefused(sceneText(kSphere, two), "lights[1].intensity", "the total power of lights[0..1] reaches");
  // Just under the bound: loads, and the float quantities the photon budget and
  // emission use are finite.
  Scene s = parseScene(sceneText(), "v.json", {"lights[0].intensity=7.9e28"});
  const Color power = lightPower(s.lights[0], SceneSphere{});
  EXPECT_TRUE(isFinite(power));
  EXPECT_LE(maxComponent(power), kMaxPower);
  EXPECT_TRUE(std::isfinite(luminance(power) * 1e8f));  // headroom left for sums
  EXPECT_TRUE(std::isfinite(classicPhotonWeight(s.lights[0])));
}

TEST(FloatValidation, GatherRadiiHaveAFiniteNonZeroSquare) {
  // 1e-30 squared is 0 in float (a division by zero); 1e20 squared is +inf.
  expectRefused(sceneText(), "photons.radius", "must be 0 or between 1e-18 and 1e+15",
                {"photons.radius=1e-30"});
  expectRefused(sceneText(), "photons.max_radius", "its square must be a normal float",
                {"photons.max_radius=1e20"});
  Scene s = parseScene(sceneText(), "v.json", {"photons.radius=1e-18", "photons.max_radius=1e15"});
  EXPECT_GT(s.photons.radius * s.photons.radius, 0.0f);
  EXPECT_TRUE(std::isfinite(s.photons.maxRadius * s.photons.maxRadius));
  EXPECT_EQ(errorOf(sceneText(), {"photons.radius=0", "photons.max_radius=0"}), "");
}

TEST(FloatValidation, OverriddenValuesGetTheSameChecks) {
  const std::string message = errorOf(sceneText(), {"objects[0].radius=1e-50"});
  EXPECT_EQ(message.rfind("v.json: objects[0].radius: ", 0), 0u) << message;
  EXPECT_NE(message.find("(value from --set)"), std::string::npos) << message;
}
