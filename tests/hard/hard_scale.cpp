// Hard cases, class "scale": one scene multiplied by 1e-5 .. 1e6 renders the same
// image in both models (no holes on shared edges, no black glass, no leaks), and the
// reported 1e-5 glass sphere and 1e-3/1e4/1e6 Cornell rooms stay whole.
#include "hard/hard_support.h"

using namespace penumbra;
using namespace penumbra::hard;

namespace {

const double kScales[] = {1e-5, 1e-3, 1.0, 1e4, 1e6};

enum class Lamp { Quad, Point };

constexpr double kQuadRadiance = 15.0;  // W/(sr m^2): scale-invariant
constexpr double kPointIntensity = 1.5;  // W/sr at scale 1, times s^2 at scale s

// A Cornell room of quads sharing edges (the reported holes), a box standing on the
// floor (its own shared edges, and a bottom face coplanar with the floor), a mirror
// sphere, a glass sphere and a 0.02-thick glass slab in front of the box. Every
// length is multiplied by s; radiance is kept: a quad light's radiance does not
// change with s, a point light's intensity goes with s^2 (irradiance I / d^2).
std::string sceneJson(double s, const std::string& model, Lamp lamp) {
  auto v = [s](double x, double y, double z) { return vec(x * s, y * s, z * s); };
  auto quad = [&](const char* mat, Vec3 c, Vec3 e1, Vec3 e2) {
    return std::string("{\"type\": \"quad\", \"material\": \"") + mat + "\", \"corner\": " +
           v(c.x, c.y, c.z) + ", \"edge1\": " + v(e1.x, e1.y, e1.z) + ", \"edge2\": " +
           v(e2.x, e2.y, e2.z) + "}";
  };
  std::string light =
      lamp == Lamp::Quad
          // A 0.6 x 0.6 panel just under the ceiling, emitting downwards.
          ? "{\"type\": \"quad\", \"corner\": " + v(-0.3, 1.98, -0.3) + ", \"edge1\": " + v(0.6, 0, 0) +
                ", \"edge2\": " + v(0, 0, 0.6) + ", \"radiance\": " + num(kQuadRadiance) + "}"
          : "{\"type\": \"point\", \"position\": " + v(0, 1.8, 0) + ", \"intensity\": " +
                num(kPointIntensity * s * s) + "}";
  const bool glass = lamp == Lamp::Quad;  // the point-light room stays opaque: see the bound
  std::string objects = quad("white", {-1, 0, 1}, {2, 0, 0}, {0, 0, -2}) + ",\n" +   // floor
                        quad("white", {-1, 2, -1}, {2, 0, 0}, {0, 0, 2}) + ",\n" +   // ceiling
                        quad("white", {-1, 0, -1}, {2, 0, 0}, {0, 2, 0}) + ",\n" +   // back
                        quad("red", {-1, 0, 1}, {0, 0, -2}, {0, 2, 0}) + ",\n" +     // left
                        quad("green", {1, 0, -1}, {0, 0, 2}, {0, 2, 0}) + ",\n" +    // right
                        "{\"type\": \"box\", \"material\": \"white\", \"min\": " + v(-0.7, 0, -0.7) +
                        ", \"max\": " + v(-0.2, 0.6, -0.2) + "},\n" +
                        "{\"type\": \"sphere\", \"material\": \"mirror\", \"center\": " + v(0.5, 0.3, -0.5) +
                        ", \"radius\": " + num(0.3 * s) + "}";
  if (glass)
    objects += ",\n{\"type\": \"sphere\", \"material\": \"glass\", \"center\": " + v(0.4, 0.3, 0.35) +
               ", \"radius\": " + num(0.3 * s) + "},\n" +
               "{\"type\": \"box\", \"material\": \"glass\", \"min\": " + v(-0.8, 0.0, 0.45) +
               ", \"max\": " + v(-0.1, 0.9, 0.47) + "}";
  return R"({
  "camera": {"position": )" + v(0, 1, 3.2) + R"(, "look_at": )" + v(0, 1, 0) + R"(, "fov": 55,
             "width": 64, "height": 64, "spp": 1},
  "lights": [)" + light + R"(],
  "materials": {
    "white": {"diffuse": 0.73},
    "red": {"diffuse": [0.63, 0.065, 0.05]},
    "green": {"diffuse": [0.14, 0.45, 0.091]},
    "mirror": {"ambient": 0, "diffuse": 0, "reflective": {"kr": 1}},
    "glass": {"ambient": 0, "diffuse": 0, "transparent": {"ior": 1.5}}
  },
  "objects": [)" + objects + R"(],
  "render": {"model": ")" + model + R"(", "max_depth": 8, "light_samples": 4, "seed": 1},
  "photons": {"gate": "off", "shadow": 0, "global": 30000, "caustic": 30000,
              "k_global": 50, "k_caustic": 30, "max_bounces": 8}
})";
}

// The brightest radiance the scene can send to the camera.
// Physical, quad light: radiance is conserved along rays and no surface reflects more
// than it receives (albedo <= 0.73, mirror kr = 1, lossless glass), so no pixel exceeds
// the emitter's radiance L; the camera sees the panel itself at exactly L.
// Physical, point light I (opaque room): direct radiance <= rho/pi * I / d^2, d = 0.2
// (light to ceiling, the nearest surface), and each bounce multiplies by <= rho, so
// all of it <= rho/pi * I/d^2 / (1 - rho); the mirror shows those same radiances.
// Classic: a surface adds ambient (0.1 * 1) plus k_d times the incidence, a quad light's
// per-sample incidence L A cos cos / r^2 <= L A / d^2 (A = 0.36; d >= 0.6: the side
// walls are 0.7 from the panel's edge, everything else it faces is further) and a
// point light's I / d^2 (d = 0.2); mirror and glass pass at most the sum of their children, so a
// camera tree of depth 8 is <= 9 x (that local term); and the panel itself is L.
double maxRadiance(const std::string& model, Lamp lamp) {
  const double rho = 0.73, pi = 3.14159265358979;
  if (model == "physical")
    return lamp == Lamp::Quad ? kQuadRadiance * (1 + 1e-5)
                              : rho / pi * kPointIntensity / (0.2 * 0.2) / (1 - rho);
  const double incidence = lamp == Lamp::Quad ? kQuadRadiance * 0.36 / (0.6 * 0.6)
                                              : kPointIntensity / (0.2 * 0.2);
  return std::max(lamp == Lamp::Quad ? kQuadRadiance : 0.0, 9.0 * (0.1 + rho * incidence));
}

struct Case {
  std::string model;
  Lamp lamp;
};
// Keeps GoogleTest (and so ctest's test names) from printing the struct's bytes.
void PrintTo(const Case& c, std::ostream* os) { *os << c.model << (c.lamp == Lamp::Quad ? " quad" : " point"); }

class HardScale : public ::testing::TestWithParam<Case> {};

// Every scale against scale 1. Tolerance: RMSE <= 1.5 x the seed-to-seed RMSE of the
// scale-1 render (the photon and light-sample noise: the same seed gives correlated
// noise at every scale, so a correct renderer sits well inside it) + 0.01 absolute (a
// few silhouette pixels flip between objects when the camera rays round differently;
// one flipped pixel of a 64 x 64 image with a jump of 0.5 is an RMSE of 0.008).
// Holes: no pixel bright (> 0.2) at scale 1 may fall below 25% of every pixel around
// it (countIsolatedHoles: a pixel centre exactly on an edge may flip to the face
// beside it, which is not a hole); at most 1, or twice what two seeds show.
TEST_P(HardScale, SameImageAtEveryScale) {
  const Case& c = GetParam();
  const double bound = maxRadiance(c.model, c.lamp);
  RenderResult ref = renderJson(sceneJson(1.0, c.model, c.lamp));
  RenderResult other = renderJson(sceneJson(1.0, c.model, c.lamp), {"render.seed=7"});
  expectSane(ref, bound, "scale 1");
  expectSane(other, bound, "scale 1, seed 7");
  const double noise = rmse(ref.image, other.image);
  // With area-light sampling noise, a pixel on a shadow's edge can drop below 25% of
  // itself from one seed to the next: the hole budget grows by what the seeds show.
  const int noiseHoles = countIsolatedHoles(ref.image, other.image);
  dump(c.model + "_" + std::to_string(int(c.lamp)) + "_1", ref.image);
  ASSERT_GT(meanPixel(ref.image), 0.05) << "the reference render is (nearly) black";
  for (double s : kScales) {
    if (s == 1.0) continue;
    RenderResult r = renderJson(sceneJson(s, c.model, c.lamp));
    const std::string what = "scale " + num(s);
    expectSane(r, bound, what);
    const double e = rmse(ref.image, r.image);
    const int holes = countIsolatedHoles(ref.image, r.image);
    std::printf("%s %s: RMSE %.5f (seed noise %.5f), holes %d, mean %.4f vs %.4f\n", c.model.c_str(),
                what.c_str(), e, noise, holes, meanPixel(r.image), meanPixel(ref.image));
    dump(c.model + "_" + std::to_string(int(c.lamp)) + "_" + num(s), r.image);
    EXPECT_LE(e, 1.5 * noise + 0.01) << what << " (seed-to-seed RMSE " << noise << ")"
                                     << worstPixels(ref.image, r.image);
    EXPECT_LE(holes, std::max(1, 2 * noiseHoles)) << what << " (seed-to-seed " << noiseHoles << ")" << ": holes (bright at scale 1, < 25% of it here)" << worstPixels(ref.image, r.image);
  }
}

INSTANTIATE_TEST_SUITE_P(Rooms, HardScale,
                         ::testing::Values(Case{"physical", Lamp::Quad}, Case{"classic", Lamp::Quad},
                                           Case{"physical", Lamp::Point}, Case{"classic", Lamp::Point}),
                         [](const auto& tp) {
                           return std::string(tp.param.model == "physical" ? "Physical" : "Classic") +
                                  (tp.param.lamp == Lamp::Quad ? "QuadLitRoomWithGlass" : "PointLitRoom");
                         });

// The reported failure: a glass sphere scaled by 1e-5 rendered black. A sphere in
// front of a lit wall, seen through: at 1e-5 its pixels carry the wall's light at
// the same brightness as at scale 1 (classic, point light: no noise at all), within
// 2% on the sphere's mean and with no holes.
std::string glassSphereJson(double s) {
  auto v = [s](double x, double y, double z) { return vec(x * s, y * s, z * s); };
  return R"({"camera": {"position": )" + v(0, 0, 4) + R"(, "look_at": )" + v(0, 0, 0) +
         R"(, "fov": 30, "width": 48, "height": 48},
  "lights": [{"type": "point", "position": )" + v(0, 0, 3) + R"(, "intensity": )" + num(9 * s * s) + R"(}],
  "materials": {"wall": {"ambient": 0, "diffuse": 0.8},
                "glass": {"ambient": 0, "diffuse": 0, "transparent": {"ior": 1.5}}},
  "objects": [{"type": "quad", "material": "wall", "corner": )" + v(-5, -5, -1) + R"(, "edge1": )" +
         v(10, 0, 0) + R"(, "edge2": )" + v(0, 10, 0) + R"(},
              {"type": "sphere", "material": "glass", "center": )" + v(0, 0, 0) + R"(, "radius": )" +
         num(0.6 * s) + R"(}],
  "render": {"max_depth": 8},
  "photons": {"gate": "off", "shadow": 0}})";
}

TEST(HardScaleGlass, GlassSphereAtOneHundredThousandthIsNotBlack) {
  RenderResult ref = renderJson(glassSphereJson(1.0));
  RenderResult tiny = renderJson(glassSphereJson(1e-5));
  // Classic bound: wall k_d I / d^2 = 0.8 * 9 / 16 at its nearest, the glass passes at
  // most the sum of its children over 9 levels.
  const double bound = 9.0 * 0.8 * 9.0 / 16.0;
  expectSane(ref, bound, "scale 1");
  expectSane(tiny, bound, "scale 1e-5");
  // The sphere covers the centre of the image: compare the central 16 x 16 pixels.
  double a = 0, b = 0;
  for (int y = 16; y < 32; ++y)
    for (int x = 16; x < 32; ++x) {
      a += meanOf(ref.image.at(x, y));
      b += meanOf(tiny.image.at(x, y));
    }
  ASSERT_GT(a, 0.0);
  EXPECT_NEAR(b / a, 1.0, 0.02) << "sphere mean at 1e-5 vs at 1";
  EXPECT_EQ(countHoles(ref.image, tiny.image, 0.05f), 0);
}

}  // namespace
