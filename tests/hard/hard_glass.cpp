// Hard cases, class "glass": thin slabs, the critical angle, a camera inside glass,
// nested and intersecting glass, ior 1 (must be invisible) and ior < 1.
#include "hard/hard_support.h"

using namespace penumbra;
using namespace penumbra::hard;

namespace {

// Textbook unpolarised Fresnel reflectance, in double.
double fresnel(double cosI, double n1, double n2) {
  double sinT = n1 / n2 * std::sqrt(std::max(0.0, 1.0 - cosI * cosI));
  if (sinT >= 1.0) return 1.0;
  double cosT = std::sqrt(1.0 - sinT * sinT);
  double rs = (n1 * cosI - n2 * cosT) / (n1 * cosI + n2 * cosT);
  double rp = (n1 * cosT - n2 * cosI) / (n1 * cosT + n2 * cosI);
  return 0.5 * (rs * rs + rp * rp);
}

// A wall at z = 0 lit by a point light at z = 0.5 in front of it, seen by a narrow
// camera at z = 5 through a glass slab [z0, z0 + thickness] that covers the view (or
// no slab). The light sits between slab and wall, so the slab only filters the view.
std::string slabJson(const std::string& model, double thickness, double halfWidth) {
  std::string slab = thickness > 0
      ? ",\n{\"type\": \"box\", \"material\": \"glass\", \"min\": " + vec(-halfWidth, -halfWidth, 1) +
            ", \"max\": " + vec(halfWidth, halfWidth, 1 + thickness) + "}"
      : "";
  return R"({"camera": {"position": [0, 0, 5], "look_at": [0, 0, 0], "fov": 10, "width": 32, "height": 32},
  "lights": [{"type": "point", "position": [0, 0, 0.5], "intensity": 1}],
  "materials": {"wall": {"ambient": 0, "diffuse": 0.8},
                "glass": {"ambient": 0, "diffuse": 0, "transparent": {"ior": 1.5}}},
  "objects": [{"type": "quad", "material": "wall", "corner": [-5, -5, 0], "edge1": [10, 0, 0],
               "edge2": [0, 10, 0]})" + slab + R"(],
  "render": {"model": ")" + model + R"(", "max_depth": 10},
  "photons": {"gate": "off", "shadow": 0, "global": 0, "caustic": 0}})";
}

// Mean over the central 8 x 8 pixels, whose rays are within 1.2 degrees of the normal.
double centre(const Image& im) {
  double s = 0;
  for (int y = 12; y < 20; ++y)
    for (int x = 12; x < 20; ++x) s += meanOf(im.at(x, y));
  return s / 64.0;
}

class HardGlassSlab : public ::testing::TestWithParam<std::string> {};

// A non-absorbing slab at normal incidence passes (1-R)^2 sum R^2k = (1-R)/(1+R) of
// what is behind it, R = ((n-1)/(n+1))^2 = 0.04 for n = 1.5: 0.92308. max_depth 10 and
// min_weight 0.001 keep the k = 0, 1 terms ((1-R)^2 (1 + R^2) = 0.923075; the rest is
// < 3e-6), and 1.2 degrees off normal moves R by < 1e-5. Tolerance 0.002 on the ratio.
// The reported failure (a 1e-6 slab crossed as one surface) gives 1 - R = 0.96.
TEST_P(HardGlassSlab, ThinSlabTransmitsTheAnalyticFraction) {
  const std::string model = GetParam();
  // Bound: the wall's radiance where it is nearest the light, d = 0.5:
  // physical rho/pi I / d^2, classic k_d I / d^2 (no 1/pi); glass passes <= 1.
  const double bound = (model == "physical" ? 0.8 / 3.14159265 : 0.8) * 1.0 / 0.25;
  const double r = 0.04, expected = (1 - r) * (1 - r) * (1 + r * r);
  RenderResult none = renderJson(slabJson(model, 0, 0));
  expectSane(none, bound, "no slab");
  ASSERT_GT(centre(none.image), 0.1);
  // Half-widths 0.5 (the view at z = 1 is 0.35 wide) and 3: a hit's error bound may
  // follow its own coordinates, not how far the slab's corners reach.
  for (double half : {0.5, 3.0}) {
    RenderResult thick = renderJson(slabJson(model, 1e-2, half));
    RenderResult thin = renderJson(slabJson(model, 1e-6, half));
    const std::string what = model + ", half-width " + num(half);
    expectSane(thick, bound, what + ", 1e-2 slab");
    expectSane(thin, bound, what + ", 1e-6 slab");
    const double tThick = centre(thick.image) / centre(none.image);
    const double tThin = centre(thin.image) / centre(none.image);
    std::printf("%s: transmitted 1e-2 %.6f, 1e-6 %.6f, expected %.6f\n", what.c_str(), tThick, tThin,
                expected);
    EXPECT_NEAR(tThick, expected, 0.002) << what << ", 1e-2 slab";
    EXPECT_NEAR(tThin, expected, 0.002) << what << ", 1e-6 slab (0.96 = crossed as one surface)";
    EXPECT_NEAR(tThin, tThick, 0.002) << what;
    EXPECT_EQ(countHoles(thick.image, thin.image, 0.01f, 0.5f), 0) << what;
  }
}

INSTANTIATE_TEST_SUITE_P(Models, HardGlassSlab, ::testing::Values("physical", "classic"),
                         [](const auto& tp) { return tp.param == "physical" ? "Physical" : "Classic"; });

// Camera inside a 200 x 1 x 200 glass slab (n = 1.5), one pixel looking up at the top
// face at theta from its normal; above it a huge panel of radiance 1 facing down,
// nothing else. max_depth 1: the pixel is exactly the transmitted branch, (1 - F) L,
// the reflected branch ends on the bottom face with nothing to add. Beyond the
// critical angle asin(1/1.5) = 41.81 degrees F = 1 and the pixel is exactly 0, at any
// depth (every bounce between the parallel faces is again total).
std::string criticalJson(double thetaDeg, int maxDepth) {
  const double t = thetaDeg * 3.14159265358979323846 / 180.0;
  return R"({"camera": {"position": [0, 0.5, 0], "look_at": )" + vec(std::sin(t), 0.5 + std::cos(t), 0) +
         R"(, "up": [0, 0, 1], "fov": 1, "width": 1, "height": 1},
  "lights": [{"type": "quad", "corner": [-1000, 1.5, -1000], "edge1": [2000, 0, 0],
              "edge2": [0, 0, 2000], "radiance": 1}],
  "materials": {"glass": {"diffuse": 0, "transparent": {"ior": 1.5}}},
  "objects": [{"type": "box", "material": "glass", "min": [-100, 0, -100], "max": [100, 1, 100]}],
  "render": {"model": "physical", "max_depth": )" + std::to_string(maxDepth) + R"(},
  "photons": {"gate": "off", "shadow": 0, "global": 0, "caustic": 0}})";
}

TEST(HardGlass, CriticalAngleTransmitsBelowAndReflectsTotallyAbove) {
  const double critical = std::asin(1 / 1.5) * 180 / 3.14159265358979323846;
  for (double theta : {0.0, 20.0, 35.0, 40.0, 41.3, 41.7, 41.95, 42.5, 50.0, 70.0, 85.0}) {
    const double f = fresnel(std::cos(theta * 3.14159265358979323846 / 180), 1.5, 1.0);
    for (int depth : {1, 8}) {
      RenderResult r = renderJson(criticalJson(theta, depth));
      expectSane(r, 1.0, "theta " + num(theta));
      const double got = r.image.at(0, 0).r;
      if (theta > critical) {
        EXPECT_EQ(got, 0.0) << "theta " << theta << " > critical " << critical << ": light leaked through TIR";
      } else if (depth == 1) {
        // 2e-3: float rounding of the camera ray and of Fresnel close to the critical
        // angle, where dF/dtheta is steep (41.7 degrees: 0.11 of it in the last 0.1 deg).
        EXPECT_NEAR(got, 1.0 - f, 2e-3) << "theta " << theta << ", textbook F " << f;
      } else {
        // Deeper: the reflected branch bounces off the bottom face and returns a part
        // F^2 (1 - F) ...: between (1 - F) and (1 - F) / (1 - F^2) = 1 / (1 + F).
        EXPECT_GE(got, 1.0 - f - 2e-3) << "theta " << theta;
        EXPECT_LE(got, 1.0 / (1.0 + f) + 2e-3) << "theta " << theta;
      }
    }
  }
}

// The camera at the centre of a glass sphere in the room. Classic with a point light
// (no sampling noise), where glass does not shadow (tint 1): every camera ray leaves the sphere along its normal, so a
// pixel is (1 - R) of what the same ray sees without the sphere (R = 0.04 at normal
// incidence) plus the reflected branch, which crosses the sphere and brings back
// R (1 - R) of the opposite view: <= 0.04 x the brightest pixel. Tolerance 1e-3 +
// 1e-3 relative for float rounding of the exit point. Physical: finite, bounded, not
// black (the sphere's caustic photons and blocked shadow rays change the room).
TEST(HardGlass, CameraInsideGlassSphereSeesTheRoom) {
  const std::string sphere = R"(,
    {"type": "sphere", "material": "glass", "center": [0.013, 1.021, 0.6], "radius": 0.3})";
  // Off the room's axis, so that no pixel centre looks exactly along a shared edge.
  const std::vector<std::string> inside = {"camera.position=[0.013, 1.021, 0.6]", "camera.look_at=[0.05, 1, -1]",
                                           "camera.fov=90", kRoomPointLight};
  RenderResult without = renderJson(roomJson("classic", ""), inside);
  RenderResult with = renderJson(roomJson("classic", sphere), inside);
  expectSane(with, classicPointRoomBound(), "classic, inside glass");
  const float brightest = maxPixel(without.image);
  int below = 0, above = 0;
  for (size_t i = 0; i < with.image.pixels.size(); ++i) {
    const double w = meanOf(without.image.pixels[i]), g = meanOf(with.image.pixels[i]);
    if (g < 0.96 * w - 1e-3 - 1e-3 * w) ++below;
    if (g > 0.96 * w + 0.04 * brightest + 1e-3 + 1e-3 * w) ++above;
  }
  EXPECT_EQ(below, 0) << "pixels darker than (1 - R) of the view without the sphere:"
                      << worstPixels(without.image, with.image);
  EXPECT_EQ(above, 0) << "pixels brighter than (1 - R) view + R (1 - R) brightest";

  // Physical with the room's quad light (radiance bound L).
  std::vector<std::string> insideQuad(inside.begin(), inside.end() - 1);
  RenderResult phys = renderJson(roomJson("physical", sphere), insideQuad);
  RenderResult physWithout = renderJson(roomJson("physical", ""), insideQuad);
  expectSane(phys, roomBound("physical"), "physical, inside glass");
  EXPECT_GT(meanPixel(phys.image), 0.5 * meanPixel(physWithout.image)) << "black from inside glass";
}

// ior 1 and tint 1: the glass is not there. Classic (where glass casts no shadow):
// the image equals the room without it to float noise (1e-4 absolute + 1e-4
// relative per pixel; the continuing ray starts one error bound further along).
// The sphere, the mirror that shows it, and the grazing silhouette (cos -> 0, the
// Fresnel formula is 0/0 there with n1 = n2) are all in view.
TEST(HardGlass, IorOneIsInvisible) {
  const std::string base = R"(,
    {"type": "sphere", "material": "mirror", "center": [0.5, 0.3, -0.5], "radius": 0.3})";
  const std::string invisible = base + R"(,
    {"type": "sphere", "material": "air", "center": [-0.2, 0.7, 0.1], "radius": 0.45},
    {"type": "box", "material": "air", "min": [0.1, 0.2, 0.3], "max": [0.6, 0.5, 0.5]})";
  const std::string air = R"(,
    "air": {"ambient": 0, "diffuse": 0, "transparent": {"ior": 1}})";
  RenderResult a = renderJson(roomJson("classic", base, air), {kRoomPointLight});
  RenderResult b = renderJson(roomJson("classic", invisible, air), {kRoomPointLight});
  expectSane(b, classicPointRoomBound(), "classic ior 1");
  int off = 0;
  for (size_t i = 0; i < a.image.pixels.size(); ++i) {
    const Color d = glm::abs(a.image.pixels[i] - b.image.pixels[i]);
    if (maxComponent(d) > 1e-4f + 1e-4f * maxComponent(a.image.pixels[i])) ++off;
  }
  EXPECT_EQ(off, 0) << "pixels where the ior-1 glass is visible:" << worstPixels(a.image, b.image);
  // Physical: glass blocks shadow rays, so it is not invisible there; still sane.
  expectSane(renderJson(roomJson("physical", invisible, air)), roomBound("physical"), "physical ior 1");
}

// ior < 1 (an air bubble in a denser world): total internal reflection from outside.
// Sane and bounded in both models, and the sphere's centre is not black (at normal
// incidence it transmits 1 - ((1 - n) / (1 + n))^2).
TEST(HardGlass, IorBelowOneIsSaneAndNotBlack) {
  const std::string obj = R"(,
    {"type": "sphere", "material": "bubble", "center": [0, 1, 0], "radius": 0.4})";
  for (const char* ior : {"0.7", "0.25"}) {
    const std::string mat = std::string(R"(,
    "bubble": {"ambient": 0, "diffuse": 0, "transparent": {"ior": )") + ior + "}}";
    for (const std::string model : {"physical", "classic"}) {
      RenderResult r = renderJson(roomJson(model, obj, mat));
      expectSane(r, roomBound(model), model + " ior " + ior);
      EXPECT_GT(meanOf(r.image.at(24, 24)), 0.01f) << model << " ior " << ior << ": black centre";
    }
  }
}

// Nested (a sphere in a sphere, a sphere in a box, equal and different ior) and
// intersecting glass (two overlapping spheres, a box through a sphere). The renderer
// assumes air outside every interface, so these are not physically exact, but each
// Fresnel split adds to 1: the room's bound holds, nothing is NaN, no ray tree runs away.
TEST(HardGlass, NestedAndIntersectingGlassAreSane) {
  const std::string obj = R"(,
    {"type": "sphere", "material": "glass", "center": [-0.5, 0.45, 0], "radius": 0.4},
    {"type": "sphere", "material": "water", "center": [-0.5, 0.45, 0], "radius": 0.2},
    {"type": "sphere", "material": "glass", "center": [-0.5, 0.45, 0], "radius": 0.1},
    {"type": "box", "material": "glass", "min": [0.1, 0, -0.6], "max": [0.7, 0.6, 0]},
    {"type": "sphere", "material": "water", "center": [0.4, 0.3, -0.3], "radius": 0.2},
    {"type": "sphere", "material": "glass", "center": [0.2, 1.2, 0.2], "radius": 0.3},
    {"type": "sphere", "material": "water", "center": [0.45, 1.2, 0.2], "radius": 0.3},
    {"type": "box", "material": "glass", "min": [-0.2, 0.9, -0.1], "max": [0.9, 1.05, 0.5]})";
  const std::string mat = R"(,
    "water": {"ambient": 0, "diffuse": 0, "transparent": {"ior": 1.33, "tint": [0.9, 0.95, 1]}})";
  for (const std::string model : {"physical", "classic"}) {
    for (int depth : {8, 64}) {
      RenderResult r = renderJson(roomJson(model, obj, mat), {"render.max_depth=" + std::to_string(depth)});
      expectSane(r, roomBound(model, depth), model + " depth " + std::to_string(depth));
      EXPECT_GT(meanPixel(r.image), 0.02) << model;
    }
  }
}

}  // namespace
