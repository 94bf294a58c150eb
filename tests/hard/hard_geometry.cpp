// Hard cases, class "geometry": grazing rays on large planes, coplanar faces
// (z-fighting), and sliver and zero-area triangles in an OBJ the test writes.
#include "hard/hard_support.h"
#include <cmath>

using namespace penumbra;
using namespace penumbra::hard;

namespace {

// A 2e6-wide floor made of two quads sharing the edge x = 0 (it runs away from the
// camera, so grazing rays meet it over its whole length), a camera 1e-2 above it
// looking nearly along it, and a point light either high or 1e-3 above the floor.
std::string planeJson(const std::string& model, double lightHeight) {
  return R"({"camera": {"position": [0.3, 0.01, 0], "look_at": [0, 0, -10], "fov": 40,
             "width": 64, "height": 48},
  "lights": [{"type": "point", "position": )" + vec(0.5, lightHeight, -3) + R"(, "intensity": 20}],
  "materials": {"floor": {"ambient": 0, "diffuse": 0.8}},
  "objects": [
    {"type": "quad", "material": "floor", "corner": [-1e6, 0, 1e6], "edge1": [1e6, 0, 0], "edge2": [0, 0, -2e6]},
    {"type": "quad", "material": "floor", "corner": [0, 0, 1e6], "edge1": [1e6, 0, 0], "edge2": [0, 0, -2e6]}],
  "render": {"model": ")" + model + R"("},
  "photons": {"gate": "off", "shadow": 0, "global": 0, "caustic": 0}})";
}

// A plane cannot shadow itself: with shadow rays on, every pixel must equal the
// render with render.shadows = false (1e-6 relative: the same incidence, computed
// once with and once without a visibility test). A self-intersecting shadow ray
// (acne) darkens a pixel; a ray slipping through the shared edge is a hole.
// Bound: rho I cos / r^2 (x 1/pi physical) with cos = h / r and r >= h, the light's
// height: <= rho I / h^2, reached only right under the light.
TEST(HardGeometry, GrazingRaysOnLargePlanesHaveNoAcneOrHoles) {
  for (const std::string model : {"physical", "classic"}) {
    for (double h : {2.0, 1e-3}) {
      const std::string what = model + ", light height " + num(h);
      RenderResult on = renderJson(planeJson(model, h));
      RenderResult off = renderJson(planeJson(model, h), {"render.shadows=false"});
      const double bound = (model == "physical" ? 0.8 / 3.14159265 : 0.8) * 20 / (h * h);
      expectSane(on, bound, what);
      expectSane(off, bound, what + ", no shadows");
      int darker = 0, lit = 0;
      for (size_t i = 0; i < on.image.pixels.size(); ++i) {
        const float a = maxComponent(on.image.pixels[i]), b = maxComponent(off.image.pixels[i]);
        if (a < b * (1 - 1e-6f)) ++darker;
        if (b > 0) ++lit;
      }
      EXPECT_GT(lit, 64 * 20) << what << ": the floor should fill the lower half";
      EXPECT_EQ(darker, 0) << what << ": pixels the plane shadowed itself (acne) or holes";
    }
  }
}

// Coplanar faces: a red and a green quad in the same plane overlapping on the back
// wall, a box whose bottom lies in the floor, and two back-to-back quads (one plane,
// opposite normals). Whichever face wins a pixel, the pixel must be what that face
// alone gives (classic, point light: deterministic, so 1e-5 relative), the render
// is identical on 1 and 2 threads and from run to run, and sane.
std::string coplanarJson(const std::string& back) {
  return R"({"camera": {"position": [0, 1, 3.2], "look_at": [0, 1, 0], "fov": 55, "width": 48, "height": 48},
  "lights": [{"type": "point", "position": [0, 1.8, 0.5], "intensity": 2}],
  "materials": {"white": {"diffuse": 0.73}, "red": {"diffuse": [0.7, 0.1, 0.1]},
                "green": {"diffuse": [0.1, 0.7, 0.1]}},
  "objects": [
    {"type": "quad", "material": "white", "corner": [-1, 0, 1], "edge1": [2, 0, 0], "edge2": [0, 0, -2]},
    {"type": "box", "material": "white", "min": [-0.6, 0, -0.6], "max": [-0.1, 0.5, -0.1]},
    {"type": "quad", "material": "white", "corner": [0.2, 0, -0.3], "edge1": [0, 0, 0.6], "edge2": [0, 0.8, 0]},
    {"type": "quad", "material": "white", "corner": [0.2, 0, -0.3], "edge1": [0, 0.8, 0], "edge2": [0, 0, 0.6]})" +
         back + R"(],
  "render": {"max_depth": 4},
  "photons": {"gate": "off", "shadow": 0}})";
}

TEST(HardGeometry, CoplanarFacesAreDeterministicAndShowOneFace) {
  const std::string red = R"(,
    {"type": "quad", "material": "red", "corner": [-1, 0, -1], "edge1": [2, 0, 0], "edge2": [0, 2, 0]})";
  const std::string green = R"(,
    {"type": "quad", "material": "green", "corner": [-0.5, 0.5, -1], "edge1": [1.5, 0, 0], "edge2": [0, 1.5, 0]})";
  RenderResult both = renderJson(coplanarJson(red + green));
  RenderResult again = renderJson(coplanarJson(red + green));
  RenderResult one = renderJson(coplanarJson(red + green), {}, "scene", 1);
  RenderResult redOnly = renderJson(coplanarJson(red));
  RenderResult greenOnly = renderJson(coplanarJson(green));
  // Classic bound: ambient 0.1 + k_d I / d^2, d = 1.04 from the light to the nearest
  // surface (the back-to-back quads' top corner; the floor is 1.8 below it).
  const double bound = 0.1 + 0.73 * 2 / (1.0 * 1.0);
  expectSane(both, bound, "coplanar");
  EXPECT_EQ(differingPixels(both.image, again.image, 0.0f), 0) << "not deterministic";
  EXPECT_EQ(differingPixels(both.image, one.image, 0.0f), 0) << "1 vs 2 threads";
  int neither = 0;
  for (size_t i = 0; i < both.image.pixels.size(); ++i) {
    auto near = [&](const Image& im) {
      return maxComponent(glm::abs(both.image.pixels[i] - im.pixels[i])) <=
             1e-5f * (1 + maxComponent(im.pixels[i]));
    };
    if (!near(redOnly.image) && !near(greenOnly.image)) ++neither;
  }
  EXPECT_EQ(neither, 0) << "pixels that are neither the red nor the green face's shading";
}

// An OBJ floor [-1, 1]^2 (y = 0) as a fan from the corner (-1, -1): its rim points
// crowd towards the far corner with cubic spacing, so the fan's triangles are needles
// down to ~1e-5 wide and 2 long (aspect 1e5); plus zero-area triangles (a repeated
// index, a repeated position, three collinear rim points) mixed in. No normals in the
// file: the loader computes them, and must skip the zero-area faces (no NaN).
std::string sliverObj() {
  std::string obj = "v -1 0 -1\n";
  const int n = 48;
  int count = 1;
  std::vector<int> rim;
  auto vert = [&](double x, double z) {
    obj += "v " + num(x) + " 0 " + num(z) + "\n";
    rim.push_back(++count);
  };
  // Along z = 1 from x = -1 to 1, then along x = 1 from z = 1 to -1, both crowded
  // towards the corner (1, 1).
  for (int i = 0; i <= n; ++i) vert(-1 + 2 * (1 - std::pow(1 - double(i) / n, 3)), 1);
  for (int i = 1; i <= n; ++i) vert(1, 1 - 2 * std::pow(double(i) / n, 3));
  obj += "v 1 0 1\n";  // a second vertex at the corner's position
  const int dup = ++count;
  std::string faces;
  for (size_t i = 0; i + 1 < rim.size(); ++i) {
    faces += "f 1 " + std::to_string(rim[i]) + " " + std::to_string(rim[i + 1]) + "\n";
    if (i % 8 == 0)  // a repeated index: zero area
      faces += "f 1 " + std::to_string(rim[i]) + " " + std::to_string(rim[i]) + "\n";
  }
  faces += "f " + std::to_string(rim[0]) + " " + std::to_string(rim[1]) + " " + std::to_string(rim[2]) + "\n";
  faces += "f 1 " + std::to_string(rim[n]) + " " + std::to_string(dup) + "\n";  // same position twice
  return obj + faces;
}

std::string floorJson(const std::string& model, const std::string& floor) {
  return R"({"camera": {"position": [0, 3, 2], "look_at": [0, 0, 0], "fov": 50, "width": 64, "height": 64},
  "lights": [{"type": "point", "position": [0.3, 1.5, 0.2], "intensity": 3}],
  "materials": {"floor": {"ambient": 0, "diffuse": 0.8}},
  "objects": [)" + floor + R"(],
  "render": {"model": ")" + model + R"("},
  "photons": {"gate": "off", "shadow": 0, "global": 0, "caustic": 0}})";
}

// The needle fan must render as the plain quad does: per pixel within 1e-3 + 1e-3
// relative (the interpolated normals of a planar mesh are the plane's to float
// rounding), no holes (rays slipping between needles: at most 2 pixels).
TEST(HardGeometry, SliverAndZeroAreaTrianglesRenderLikeTheirQuad) {
  const std::string obj = writeTemp("slivers", "obj", sliverObj());
  const std::string mesh = R"({"type": "mesh", "material": "floor", "file": ")" + obj + R"("})";
  const std::string quad =
      R"({"type": "quad", "material": "floor", "corner": [-1, 0, 1], "edge1": [2, 0, 0], "edge2": [0, 0, -2]})";
  for (const std::string model : {"physical", "classic"}) {
    RenderResult a = renderJson(floorJson(model, quad));
    RenderResult b = renderJson(floorJson(model, mesh), {}, "mesh_scene");
    // Bound: rho I / h^2 (x 1/pi physical), h = 1.5 the light's height.
    const double bound = (model == "physical" ? 0.8 / 3.14159265 : 0.8) * 3 / (1.5 * 1.5);
    expectSane(a, bound, model + " quad");
    expectSane(b, bound, model + " slivers");
    int off = 0;
    for (size_t i = 0; i < a.image.pixels.size(); ++i)
      if (maxComponent(glm::abs(a.image.pixels[i] - b.image.pixels[i])) >
          1e-3f + 1e-3f * maxComponent(a.image.pixels[i]))
        ++off;
    EXPECT_LE(countHoles(a.image, b.image, 0.05f), 2) << model;
    EXPECT_LE(off, 2) << model << ": pixels where the sliver mesh differs from its quad";
  }
}

}  // namespace
