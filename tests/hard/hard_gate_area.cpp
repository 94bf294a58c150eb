// Hard cases, class "gate": a "lit" verdict for an area light must give all of the
// light that reaches the point, however few light samples land on its visible part
// (a quad or disk half below the floor, a cube lamp in an open box): gated direct light
// equals ungated within the ungated render's own noise, at 1, 4 and 16 samples,
// in both models; and a small quad over a plane matches Lambert's formula.
#include "hard/hard_support.h"

using namespace penumbra;
using namespace penumbra::hard;

namespace {

// Floor (ambient 0, no specular: the closed form is the whole answer) and the
// caller's light and objects; shadow photons only, so the direct light is all.
std::string gateJson(const std::string& model, const std::string& camera, const std::string& light,
                     const std::string& objects, const std::string& materials = "") {
  return R"({"camera": )" + camera + R"(,
  "lights": [)" + light + R"(],
  "materials": {"white": {"ambient": 0, "diffuse": 0.6, "specular": 0})" + materials + R"(},
  "objects": [
    {"type": "quad", "material": "white", "corner": [-3, 0, 3], "edge1": [6, 0, 0], "edge2": [0, 0, -6]})" +
         objects + R"(],
  "render": {"model": ")" + model + R"(", "max_depth": 1},
  "photons": {"gate": "on", "shadow": 60000, "k_shadow": 20, "indirect": 0, "global": 0, "caustic": 0}})";
}

RenderResult renderAt(const std::string& json, const std::string& model, int samples, bool gate) {
  std::vector<std::string> o = {"render.light_samples=" + std::to_string(samples),
                                std::string("photons.gate=") + (gate ? "on" : "off")};
  if (model == "physical") o.push_back("render.aov=direct");
  return renderJson(json, o, gate ? "gated" : "ungated");
}

// Gated against ungated over every pixel: d_i = ungated_i - gated_i are independent
// (each pixel seeds its own samples), so their mean has standard error sd(d) /
// sqrt(N). Passes when the mean difference is within 4 standard errors plus 1% of
// the mean (room for a gate verdict that is not quite right at a few pixels).
struct Comparison {
  double gated = 0.0, ungated = 0.0, se = 0.0;
  int lit = 0;
  double ratio() const { return gated / ungated; }
};
Comparison compare(const Image& gated, const Image& ungated) {
  Comparison c;
  const size_t n = gated.pixels.size();
  double sd = 0.0, sd2 = 0.0;
  for (size_t i = 0; i < n; ++i) {
    const double g = meanOf(gated.pixels[i]), u = meanOf(ungated.pixels[i]);
    c.gated += g;
    c.ungated += u;
    sd += u - g;
    sd2 += (u - g) * (u - g);
  }
  c.gated /= n;
  c.ungated /= n;
  const double mean = sd / n, var = std::max(0.0, sd2 / n - mean * mean);
  c.se = std::sqrt(var / (n - 1));
  return c;
}

// `litShare`: the least share of pixels the gate must have said lit at (the
// closed form asks it wherever light arrives; samples only where one reached).
void expectGatedEqualsUngated(const std::string& what, const std::function<std::string(const std::string&)>& scene,
                              double litShare = 0.5) {
  for (const std::string model : {"classic", "physical"}) {
    for (int samples : {1, 4, 16}) {
      const std::string w = what + ", " + model + ", " + std::to_string(samples) + " light samples";
      const std::string json = scene(model);
      RenderResult g = renderAt(json, model, samples, true), u = renderAt(json, model, samples, false);
      dump(w + " gated", g.image);
      dump(w + " ungated", u.image);
      // The gate must have been asked, and said lit for most of the image.
      EXPECT_GT(g.stats.rays.gateLit, litShare * g.image.pixels.size()) << w << ": the gate said lit too rarely";
      const Comparison c = compare(g.image, u.image);
      std::printf("%s: gated %.5f ungated %.5f ratio %.4f (se %.5f)\n", w.c_str(), c.gated, c.ungated,
                  c.ratio(), c.se);
      EXPECT_GT(c.ungated, 1e-3) << w << ": the scene is dark";
      EXPECT_LE(std::abs(c.gated - c.ungated), 4.0 * c.se + 0.01 * c.ungated)
          << w << ": gated " << c.gated << " vs ungated " << c.ungated << " (ratio " << c.ratio()
          << ", standard error " << c.se << ")";
    }
  }
}

// A camera looking steeply down at the floor in front of the light, the light
// itself out of view (its pixels would be equal in both renders anyway).
const std::string kFloorCamera =
    R"({"position": [0.03, 2.0, 1.6], "look_at": [0.0, 0, 1.2], "fov": 30, "width": 64, "height": 48, "spp": 1})";

// (a) A vertical quad light facing +z, standing half below the floor: from the
// floor only its upper half is above the horizon, and a sample on the lower half
// reaches nothing. Before a lit verdict integrated it in closed form whatever the
// samples hit, 1 sample gave about half the light.
TEST(HardGateArea, QuadHalfBelowTheFloor) {
  expectGatedEqualsUngated("quad half below the floor", [](const std::string& model) {
    return gateJson(model, kFloorCamera,
                    R"({"type": "quad", "corner": [-0.5, -0.5, 0], "edge1": [1, 0, 0], "edge2": [0, 1, 0], "radiance": 4})",
                    "");
  });
}

// A disk light facing +z, standing half below the floor as the quad above: the floor's
// horizon cuts it, so a lit verdict keeps its samples (without rays), as the sphere's
// below; at 1 sample only those landing on the upper half ask the gate.
TEST(HardGateArea, DiskHalfBelowTheFloor) {
  expectGatedEqualsUngated("disk half below the floor", [](const std::string& model) {
    return gateJson(model, kFloorCamera,
                    R"({"type": "disk", "center": [0, 0, 0], "normal": [0, 0, 1], "radius": 0.5, "radiance": 4})", "");
  }, 0.25);
}

// A disk facing down over the floor: above every floor point's horizon, so a lit
// verdict answers with its closed form.
TEST(HardGateArea, DiskOverTheFloorByItsClosedForm) {
  expectGatedEqualsUngated("disk over the floor", [](const std::string& model) {
    return gateJson(model, kFloorCamera,
                    R"({"type": "disk", "center": [0, 0.6, 0.6], "normal": [0, -1, 0.2], "radius": 0.3, "radiance": 4})", "");
  });
}

// A sphere light sunk to its centre in the floor: every floor point sees it cut by
// its horizon, where there is no closed form, so a lit verdict keeps the samples
// (without rays): unbiased before the fix too, and it must stay so.
TEST(HardGateArea, SphereHalfBelowTheFloorKeepsItsSamples) {
  expectGatedEqualsUngated("sphere half below the floor", [](const std::string& model) {
    return gateJson(model, kFloorCamera, R"({"type": "sphere", "center": [0, 0, 0], "radius": 0.4, "radiance": 4})", "");
  }, 0.25);
}

// (b) A cube lamp (an emissive box: a mesh light of 12 triangles) hanging in a box
// open at the bottom, its bottom face level with the opening. The floor under the
// lamp sees its bottom face alone, and the gate says lit there; a sample on any of
// the other five faces reaches nothing.
TEST(HardGateArea, CubeLampInAnOpenBox) {
  const std::string camera =
      R"({"position": [0.01, 0.9, 0.12], "look_at": [0.0, 0, 0], "fov": 12, "width": 48, "height": 48, "spp": 1})";
  // The open box: a lid and four walls, 0.1 outside the lamp, from the lamp's bottom up.
  const std::string box = R"(,
    {"type": "box", "material": "lamp", "min": [-0.2, 1.0, -0.2], "max": [0.2, 1.4, 0.2]},
    {"type": "quad", "material": "white", "corner": [-0.3, 1.5, -0.3], "edge1": [0.6, 0, 0], "edge2": [0, 0, 0.6]},
    {"type": "quad", "material": "white", "corner": [-0.3, 1.0, -0.3], "edge1": [0.6, 0, 0], "edge2": [0, 0.5, 0]},
    {"type": "quad", "material": "white", "corner": [-0.3, 1.0, 0.3], "edge1": [0.6, 0, 0], "edge2": [0, 0.5, 0]},
    {"type": "quad", "material": "white", "corner": [-0.3, 1.0, -0.3], "edge1": [0, 0, 0.6], "edge2": [0, 0.5, 0]},
    {"type": "quad", "material": "white", "corner": [0.3, 1.0, -0.3], "edge1": [0, 0, 0.6], "edge2": [0, 0.5, 0]})";
  expectGatedEqualsUngated("cube lamp in an open box", [&](const std::string& model) {
    return gateJson(model, camera, "", box, R"(, "lamp": {"emission": 5})");
  });
}

// Lambert's formula for a point under the centre of an a x b rectangle at height h
// (four corner rectangles): E = 2 L [X/sqrt(1+X^2) atan(Y/sqrt(1+X^2)) + (X <-> Y)],
// X = a / 2h, Y = b / 2h.
double centredRectangleIrradiance(double L, double a, double b, double h) {
  const double X = a / (2 * h), Y = b / (2 * h);
  const double sx = std::sqrt(1 + X * X), sy = std::sqrt(1 + Y * Y);
  return 2 * L * (X / sx * std::atan(Y / sx) + Y / sy * std::atan(X / sy));
}

// A 0.3 x 0.2 quad light 1 above the floor, facing down; a narrow camera sees the
// floor within ~0.01 of the point under its centre, where E changes by < 0.1%.
// Classic reflects k_d E, physical k_d / pi E; gated (closed form) and ungated
// (16 samples, averaged over the pixels) both match Lambert's formula.
TEST(HardGateArea, SmallQuadOverAPlaneMatchesLambert) {
  const double L = 4.0, kd = 0.6, pi = 3.14159265358979;
  const double E = centredRectangleIrradiance(L, 0.3, 0.2, 1.0);
  const std::string camera =
      R"({"position": [0.0, 0.5, 0.5], "look_at": [0, 0, 0], "fov": 1.5, "width": 15, "height": 15, "spp": 1})";
  const std::string light =
      R"({"type": "quad", "corner": [-0.15, 1, -0.1], "edge1": [0.3, 0, 0], "edge2": [0, 0, 0.2], "radiance": 4})";
  for (const std::string model : {"classic", "physical"}) {
    const double expected = (model == "physical" ? kd / pi : kd) * E;
    const std::string json = gateJson(model, camera, light, "");
    RenderResult g = renderAt(json, model, 16, true), u = renderAt(json, model, 16, false);
    EXPECT_GT(g.stats.rays.gateLit, 0u) << model;
    const Comparison c = compare(g.image, u.image);
    std::printf("Lambert, %s: expected %.6f gated %.6f ungated %.6f (se %.6f)\n", model.c_str(), expected,
                c.gated, c.ungated, c.se);
    EXPECT_NEAR(c.gated, expected, 2e-3 * expected) << model << ": gated";
    EXPECT_NEAR(c.ungated, expected, 4.0 * c.se + 2e-3 * expected) << model << ": ungated";
  }
}

}  // namespace
