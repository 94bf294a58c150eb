// Hard cases, class "media": coefficients of 0 and 1e30, Henyey–Greenstein at
// g = ±0.999999, media nested three deep, a camera exactly on a medium's boundary —
// each renders a finite, bounded image; a medium inside an open mesh is refused.
#include "hard/hard_cli.h"
#include "hard/hard_support.h"

using namespace penumbra;
using namespace penumbra::hard;

namespace {

// A white room's floor and back wall under a point light, a glass sphere, and `extra`
// objects; `medium` fills the scene ("" for none). Physical units: the brightest a
// wall can be is rho I / (pi d^2) at d = 1, plus what the fog and glass gather: bounded
// by 10 x that (a loose bound; NaN and Inf are what these cases hunt).
std::string roomJson(const std::string& media, const std::string& medium, const std::string& extra = "",
                     const std::string& camera = "[0, 1, 3]") {
  return R"({"camera": {"position": )" + camera + R"(, "look_at": [0, 1, 0], "fov": 50, "width": 24, "height": 24},
  "lights": [{"type": "point", "position": [0, 2, 0], "intensity": 3}],
  "media": [)" + media + R"(],
  "materials": {"white": {"diffuse": 0.7}, "glass": {"diffuse": 0, "transparent": {"ior": 1.5}}},
  "objects": [{"type": "quad", "corner": [-2, 0, 2], "edge1": [4, 0, 0], "edge2": [0, 0, -4], "material": "white"},
              {"type": "quad", "corner": [-2, 0, -2], "edge1": [4, 0, 0], "edge2": [0, 3, 0], "material": "white"},
              {"type": "sphere", "center": [0.5, 0.5, 0], "radius": 0.3, "material": "glass"})" +
         extra + R"(],
  "render": {"model": "physical", "max_depth": 8)" + (medium.empty() ? "" : R"(, "medium": ")" + medium + "\"") + R"(},
  "photons": {"gate": false, "global": 5000, "caustic": 5000, "volume": 5000, "passes": 2}})";
}

std::string fog(const std::string& name, const std::string& sigmaA, const std::string& sigmaS, const std::string& g) {
  return R"({"name": ")" + name + R"(", "sigma_a": )" + sigmaA + R"(, "sigma_s": )" + sigmaS + R"(, "g": )" + g + "}";
}

constexpr double kBound = 10.0 * 0.7 * 3.0 / 3.14159265;

TEST(HardMedia, ZeroCoefficientsAreVacuum) {
  const RenderResult r = renderJson(roomJson(fog("clear", "0", "0", "0"), "clear"));
  expectSane(r, kBound, "sigma 0");
  EXPECT_GT(meanPixel(r.image), 0.0);  // the room is lit through the clear medium
}

TEST(HardMedia, AnOpaqueMediumIsBlackNotNaN) {
  // Fog of 1e30 per unit in a box in front of the camera: nothing crosses it.
  const std::string box = R"(, {"type": "box", "min": [-3, -1, 1.5], "max": [3, 4, 2], "medium": "wall"})";
  for (const char* which : {"sigma_s", "sigma_a"}) {
    const std::string m = std::string(which) == "sigma_s" ? fog("wall", "0", "1e30", "0") : fog("wall", "1e30", "0", "0");
    const RenderResult r = renderJson(roomJson(m, "", box));
    expectSane(r, kBound, which);
    EXPECT_LE(meanPixel(r.image), 1e-6) << which;  // a wall of it covers the whole view
  }
}

TEST(HardMedia, NearlyDeltaPhaseFunctionsStayFinite) {
  for (const char* g : {"0.999999", "-0.999999"}) {
    const RenderResult r = renderJson(roomJson(fog("fog", "0.01", "0.3", g), "fog"));
    expectSane(r, kBound, std::string("g = ") + g);
  }
}

TEST(HardMedia, NestedMediaRender) {
  // Scene fog, a box of smoke in it, a sphere of ink inside the box, the glass in the fog.
  const std::string media = fog("fog", "0.01", "0.1", "0.3") + ", " + fog("smoke", "0.05", "1.0", "0.6") + ", " +
                            fog("ink", "2.0", "0.5", "-0.3");
  const std::string nested = R"(, {"type": "box", "min": [-1, 0.2, -0.8], "max": [0, 1.4, 0.2], "medium": "smoke"},
              {"type": "sphere", "center": [-0.5, 0.8, -0.3], "radius": 0.3, "medium": "ink"})";
  const RenderResult r = renderJson(roomJson(media, "fog", nested));
  expectSane(r, kBound, "nested");
  EXPECT_GT(r.stats.rays.mediumSegments, 0u);
}

TEST(HardMedia, ACameraOnAMediumBoundaryRenders) {
  // The camera sits exactly on the sphere of fog's surface (centre (0, 1, 1), radius 2).
  const std::string ball = R"(, {"type": "sphere", "center": [0, 1, 1], "radius": 2, "medium": "fog"})";
  const RenderResult r = renderJson(roomJson(fog("fog", "0.02", "0.3", "0"), "", ball, "[0, 1, 3]"));
  expectSane(r, kBound, "camera on the boundary");
}

TEST(HardMedia, AMediumInAnOpenMeshIsRefusedInOneLine) {
  const ScratchDir dir;
  const std::string open = R"(, {"type": "quad", "corner": [-1, 0.1, 1], "edge1": [2, 0, 0], "edge2": [0, 0, -2], "medium": "fog"})";
  const fs::path scene = dir.write("open.json", roomJson(fog("fog", "0.01", "0.1", "0"), "", open));
  const CliResult r = runCli("render " + quote(scene.string()) + " -o " + quote((dir / "out.png").string()));
  EXPECT_EQ(r.exitCode, 2) << r.err;
  EXPECT_EQ(occurrences(r.err, "\n"), 1u) << r.err;
  EXPECT_NE(r.err.find("objects[3].medium"), std::string::npos) << r.err;  // the file's JSON path
  EXPECT_NE(r.err.find("open"), std::string::npos) << r.err;
  EXPECT_FALSE(fs::exists(dir / "out.png"));
}

}  // namespace
