// Hard cases, class "lights": lights inside closed objects (nothing outside may be
// lit, gate on and off; the reported point light 3e-5 inside a wall) and lights
// lying exactly on surfaces.
#include "hard/hard_support.h"

using namespace penumbra;
using namespace penumbra::hard;

namespace {

// A room (floor, back and side walls; ambient 0 so unlit means 0) with a closed box
// [-0.5, 0.5] x [0, 1] x [-0.5, 0.5] on the floor and a closed opaque sphere; the
// caller puts a light inside one of them. From outside, every surface the camera
// sees faces away from the light or is hidden from it by the closed object, so the
// whole image must be exactly 0 (no float noise either: an unlit point adds nothing).
std::string closedJson(const std::string& model, const std::string& light) {
  return R"({"camera": {"position": [0.4, 1.6, 3.2], "look_at": [0, 0.6, 0], "fov": 60, "width": 48, "height": 48},
  "lights": [)" + light + R"(],
  "materials": {"white": {"ambient": 0, "diffuse": 0.73}},
  "objects": [
    {"type": "quad", "material": "white", "corner": [-2, 0, 2], "edge1": [4, 0, 0], "edge2": [0, 0, -4]},
    {"type": "quad", "material": "white", "corner": [-2, 0, -2], "edge1": [4, 0, 0], "edge2": [0, 3, 0]},
    {"type": "quad", "material": "white", "corner": [-2, 0, 2], "edge1": [0, 0, -4], "edge2": [0, 3, 0]},
    {"type": "quad", "material": "white", "corner": [2, 0, -2], "edge1": [0, 0, 4], "edge2": [0, 3, 0]},
    {"type": "box", "material": "white", "min": [-0.5, 0, -0.5], "max": [0.5, 1, 0.5]},
    {"type": "sphere", "material": "white", "center": [1.2, 0.4, -0.8], "radius": 0.4}],
  "render": {"model": ")" + model + R"(", "light_samples": 4},
  "photons": {"shadow": 20000, "k_shadow": 20, "global": 20000, "caustic": 0, "k_global": 30}})";
}

std::string pointAt(double x, double y, double z) {
  return R"({"type": "point", "position": )" + vec(x, y, z) + R"(, "intensity": 5})";
}

// Physical renders look at the direct view (the shadow rays' light) unless asked for
// the beauty: its global-map estimate leaks on its own, see PhotonsStayInside.
void expectDark(const std::string& light, const std::string& what, bool physicalBeauty = false) {
  for (const std::string model : {"physical", "classic"}) {
    for (const char* gate : {"off", "on"}) {
      const std::string w = what + ", " + model + ", gate " + gate;
      std::vector<std::string> o = {std::string("photons.gate=") + gate};
      if (model == "physical" && !physicalBeauty) o.push_back("render.aov=direct");
      if (model == "classic" && physicalBeauty) continue;
      RenderResult r = renderJson(closedJson(model, light), o);
      // The bound is 0: nothing outside the closed object can receive any light.
      dump(w, r.image);
      expectSane(r, 0.0, w);
      EXPECT_EQ(maxPixel(r.image), 0.0f) << w << ": light leaked out of the closed object";
    }
  }
}

// The reported leak: a point light 3e-5 under the box's top face lit the room
// outside when shadow rays decided (gate off): a shadow ray from the floor stopped
// 1e-4 of its length short of the light, before the box's top face. Also 3e-5
// inside a side wall. (A point light's shadow ray now stops 2^-20 of its length
// short, so 1e-6 under the face still leaks to points more than ~1 away: below what
// that margin resolves, not asserted here.)
TEST(HardLights, PointLightJustInsideAWallLeaksNothing) {
  expectDark(pointAt(0, 1 - 3e-5, 0), "3e-5 under the top");
  expectDark(pointAt(0.5 - 3e-5, 0.5, 0.1), "3e-5 inside the +x wall");
}

const std::string kQuadInBox = R"({"type": "quad", "corner": [-0.2, 0.5, -0.2], "edge1": [0, 0, 0.4],
                 "edge2": [0.4, 0, 0], "radiance": 10})";

// Lights well inside closed objects: a point light at the box's centre, one inside
// the opaque sphere, and a quad light inside the box (facing up at its lid).
TEST(HardLights, LightsInsideClosedObjectsLightNothingOutside) {
  expectDark(pointAt(0, 0.5, 0), "point in the box");
  expectDark(pointAt(1.2, 0.4, -0.8), "point in the sphere");
  expectDark(kQuadInBox, "quad light in the box");
}

// The physical beauty of the same scenes: global photons all land inside the closed
// object, yet a density estimate outside may reach them. The answer is 0 outside,
// and the estimator converges to it: with a fixed gather radius (progressive passes,
// alpha 1) a floor point gathers only photons within r, and the only photons that
// near lie on the box's inner bottom face, in the floor's own plane with the floor's
// normal, within r of the walls. r = 0.01 leaves the room dark but for at most two
// stray pixels per pass: a photon that hit within ulps of one of the box's edges and
// started its next ray a rounding error outside the other face (each pass samples
// new pixel positions, so each may catch its own; seen: up to 4 in 2 passes, 1 in the
// one pass that sampled pixel centres). The inner bottom's photons stay out where the
// disc also holds the box's inner walls' photons: they mark where the floor outside
// ends (gather/surface_share.h). The one-pass k-nearest estimate has no radius: far
// from any photon it reaches through the walls (docs/photon-maps.md), but there too
// the walls' photons keep the inner bottom out; asserted to stay on the floor near
// the box (<= 2% of the pixels) and below 1e-4 elsewhere, the ~6e-6 residue of
// photons that start a rounding error outside a face at the box's edges.
TEST(HardLights, PhotonsOfALightInsideAClosedObjectConvergeToDark) {
  const float kResidual = 1e-4f;
  for (const std::string& light : {pointAt(0, 0.5, 0), kQuadInBox}) {
    for (const char* gate : {"off", "on"}) {
      const std::string w = light.substr(0, 20) + ", gate " + gate;
      const std::string g = std::string("photons.gate=") + gate;
      RenderResult fine = renderJson(closedJson("physical", light),
                                     {g, "photons.passes=2", "photons.radius=0.01", "photons.alpha=1"});
      dump(w + " r0.01", fine.image);
      // A stray photon's pixel: its power over r = 0.01's disc, rho / pi x Phi x 2 / (pi
      // r^2) ~ 4.6, or up to 4x that beside the box, where the disc reaches past the
      // floor's edge and the estimate divides by the kernel's mass on the floor's side.
      expectSane(fine, 20.0, w + ", radius 0.01");
      int fineLit = 0;
      for (const Color& c : fine.image.pixels) fineLit += maxComponent(c) > 0.0f;
      EXPECT_LE(fineLit, 2 * 2) << w << ": radius 0.01 must converge to dark outside (2 passes)";
      RenderResult knn = renderJson(closedJson("physical", light), {g});
      dump(w, knn.image);
      expectSane(knn, 10.0, w);
      int lit = 0;
      for (const Color& c : knn.image.pixels) lit += maxComponent(c) > kResidual;
      EXPECT_LE(lit, static_cast<int>(0.02 * knn.image.pixels.size())) << w << ": " << lit << " pixels lit";
      // Above the box's base the room is dark: the top rows see walls and ceiling only.
      float top = 0.0f;
      for (int y = 0; y < 12; ++y)
        for (int x = 0; x < knn.image.width; ++x) top = std::max(top, maxComponent(knn.image.at(x, y)));
      EXPECT_LE(top, kResidual) << w;
    }
  }
}

// Lights exactly on surfaces. A point light on the floor plane (y = 0) and one on
// the box's top face: the surface it lies in gets cos = 0, everything else is lit
// as usual. A quad light lying exactly in the back wall (coplanar emitter and wall:
// z-fighting between them) and one on the box top. Bounds (physical): direct
// rho/pi I / d^2 from the nearest *other* surface (d = 0.5 for the floor light at
// (0.9, 0, 0.9): the box is 0.4 away in x and z, so d >= 0.4 -> use 0.4), times
// 1/(1 - rho) for the bounces; a quad light: its radiance L = 10. Classic: k_d I / d^2
// (no 1/pi, no bounces: no indirect map, ambient 0), or the panel itself.
TEST(HardLights, LightsOnSurfacesAreSaneAndLight) {
  const double rho = 0.73, pi = 3.14159265358979;
  struct Case {
    std::string light, what;
    double physical, classic;
  };
  const Case cases[] = {
      {pointAt(0.9, 0, 0.9), "point on the floor", rho / pi * 5 / 0.16 / (1 - rho), rho * 5 / 0.16},
      {pointAt(0, 1, 0), "point on the box top", rho / pi * 5 / 1.0 / (1 - rho), rho * 5 / 1.0},
      {R"({"type": "quad", "corner": [-1, 0.5, -2], "edge1": [2, 0, 0], "edge2": [0, 1, 0], "radiance": 10})",
       "quad in the back wall", 10 * (1 + 1e-5), std::max(10.0, rho * 10 * 2 / 0.25)},
      {R"({"type": "quad", "corner": [-0.3, 1, 0.3], "edge1": [0.6, 0, 0], "edge2": [0, 0, -0.6], "radiance": 10})",
       "quad on the box top", 10 * (1 + 1e-5), std::max(10.0, rho * 10 * 0.36 / 0.25)},
  };
  for (const Case& c : cases) {
    for (const std::string model : {"physical", "classic"}) {
      for (const char* gate : {"off", "on"}) {
        const std::string w = c.what + ", " + model + ", gate " + gate;
        RenderResult r = renderJson(closedJson(model, c.light),
                                    {std::string("photons.gate=") + gate});
        expectSane(r, model == "physical" ? c.physical : c.classic, w);
        EXPECT_GT(meanPixel(r.image), 1e-3) << w << ": a light on a surface lights nothing";
      }
    }
  }
}

}  // namespace
