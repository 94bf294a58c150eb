// Shared by the hard-case suite: render a JSON scene string through the whole
// pipeline, check it is sane (finite, bounded), and compare images.
#pragma once
#include "plan/pipeline.h"
#include "core/color.h"
#include "core/error.h"
#include "io/image_io.h"
#include <gtest/gtest.h>
#include <algorithm>
#include <cctype>
#include <cstdlib>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <functional>
#include <sstream>
#include <string>
#include <vector>

namespace penumbra::hard {

namespace fs = std::filesystem;

// A file under the system temp folder named after the running test, so parallel
// ctest runs (one process per test) never share one.
inline std::string writeTemp(const std::string& stem, const std::string& ext, const std::string& text) {
  const auto* info = ::testing::UnitTest::GetInstance()->current_test_info();
  std::string tag = info ? std::string(info->test_suite_name()) + "." + info->name() : "hard";
  for (char& c : tag)
    if (!std::isalnum(static_cast<unsigned char>(c))) c = '_';
  fs::path dir = fs::temp_directory_path() / ("penumbra_hard_" + tag);
  fs::create_directories(dir);
  fs::path path = dir / (stem + "." + ext);
  std::ofstream(path) << text;
  return path.string();
}

// Renders a scene given as JSON text, in memory, on 2 threads (the images do not
// depend on the thread count; 2 keeps the suite fair to the other jobs here).
inline RenderResult renderJson(const std::string& json, std::vector<std::string> overrides = {},
                               const std::string& stem = "scene", int threads = 2) {
  RenderRequest req;
  req.scenePath = writeTemp(stem, "json", json);
  req.overrides = std::move(overrides);
  // PENUMBRA_HARD_SET="k=v;k=v": extra overrides for every render (to bisect a failure).
  if (const char* extra = std::getenv("PENUMBRA_HARD_SET")) {
    std::stringstream in(extra);
    for (std::string kv; std::getline(in, kv, ';');)
      if (!kv.empty()) req.overrides.push_back(kv);
  }
  req.session.threads = threads;
  return runRender(req);
}

// PENUMBRA_HARD_DUMP=folder: write the image there (to look at a failure).
inline void dump(const std::string& name, const Image& im) {
  if (const char* dir = std::getenv("PENUMBRA_HARD_DUMP")) writeImage(std::string(dir) + "/" + name + ".png", im, {});
}

// Where two images differ most: "x,y a -> b" for the worst `n` pixels, for messages.
inline std::string worstPixels(const Image& a, const Image& b, int n = 5) {
  std::vector<std::pair<float, size_t>> d;
  for (size_t i = 0; i < a.pixels.size() && i < b.pixels.size(); ++i)
    d.push_back({maxComponent(glm::abs(a.pixels[i] - b.pixels[i])), i});
  std::partial_sort(d.begin(), d.begin() + std::min<size_t>(n, d.size()), d.end(),
                    [](auto& x, auto& y) { return x.first > y.first; });
  std::ostringstream out;
  for (int k = 0; k < n && k < int(d.size()); ++k) {
    size_t i = d[k].second;
    out << " (" << i % a.width << "," << i / a.width << ") " << meanOf(a.pixels[i]) << "->" << meanOf(b.pixels[i]);
  }
  return out.str();
}

inline float maxPixel(const Image& im) {
  float m = 0.0f;
  for (const Color& c : im.pixels) m = std::max(m, maxComponent(c));
  return m;
}

inline double meanPixel(const Image& im) {
  double s = 0.0;
  for (const Color& c : im.pixels) s += (double(c.r) + c.g + c.b) / 3.0;
  return im.pixels.empty() ? 0.0 : s / im.pixels.size();
}

// The sanity every hard case owes: no sample came out NaN/Inf (the renderer drops
// and counts them, so a clean-looking image can hide them), every pixel is finite,
// non-negative, and at most the scene's physically possible radiance.
inline void expectSane(const RenderResult& r, double maxRadiance, const std::string& what) {
  EXPECT_EQ(r.stats.rays.nonfiniteSamples, 0u) << what << ": NaN/Inf samples were dropped";
  int bad = 0, negative = 0, over = 0;
  float worst = 0.0f;
  for (const Color& c : r.image.pixels) {
    if (!isFinite(c)) { ++bad; continue; }
    if (std::min(c.r, std::min(c.g, c.b)) < 0.0f) ++negative;
    if (maxComponent(c) > maxRadiance) ++over;
    worst = std::max(worst, maxComponent(c));
  }
  EXPECT_EQ(bad, 0) << what << ": non-finite pixels";
  EXPECT_EQ(negative, 0) << what << ": negative pixels";
  EXPECT_EQ(over, 0) << what << ": pixels above the bound " << maxRadiance << " (brightest " << worst << ")";
}

inline double rmse(const Image& a, const Image& b) {
  EXPECT_EQ(a.pixels.size(), b.pixels.size());
  if (a.pixels.size() != b.pixels.size() || a.pixels.empty()) return 1e30;
  double s = 0.0;
  for (size_t i = 0; i < a.pixels.size(); ++i) {
    Color d = a.pixels[i] - b.pixels[i];
    s += (double(d.r) * d.r + double(d.g) * d.g + double(d.b) * d.b) / 3.0;
  }
  return std::sqrt(s / a.pixels.size());
}

// Holes: pixels that are bright (> bright) in the reference and fell below
// `fraction` of it in the other image, e.g. black specks on shared edges or black glass.
inline int countHoles(const Image& ref, const Image& other, float bright = 0.2f, float fraction = 0.25f) {
  int n = 0;
  for (size_t i = 0; i < ref.pixels.size() && i < other.pixels.size(); ++i) {
    const float r = meanOf(ref.pixels[i]);
    if (r > bright && meanOf(other.pixels[i]) < fraction * r) ++n;
  }
  return n;
}

// Holes that are not flips between faces: a pixel whose centre lies on an edge may
// show the face beside it at another scale, which a neighbour shows too. A hole is
// darker than `fraction` of every reference pixel in its 3 x 3 neighbourhood (a black
// speck where all around was bright), so flips to a darker neighbour do not count.
inline int countIsolatedHoles(const Image& ref, const Image& other, float bright = 0.2f,
                              float fraction = 0.25f) {
  int n = 0;
  for (int y = 0; y < ref.height; ++y)
    for (int x = 0; x < ref.width; ++x) {
      if (meanOf(ref.at(x, y)) <= bright) continue;
      float darkest = kInf;
      for (int dy = -1; dy <= 1; ++dy)
        for (int dx = -1; dx <= 1; ++dx) {
          const int u = x + dx, v = y + dy;
          if (u >= 0 && v >= 0 && u < ref.width && v < ref.height) darkest = std::min(darkest, meanOf(ref.at(u, v)));
        }
      if (meanOf(other.at(x, y)) < fraction * darkest) ++n;
    }
  return n;
}

inline int differingPixels(const Image& a, const Image& b, float tol) {
  int n = 0;
  for (size_t i = 0; i < a.pixels.size() && i < b.pixels.size(); ++i)
    if (maxComponent(glm::abs(a.pixels[i] - b.pixels[i])) > tol) ++n;
  return n;
}

// Shortest round-trip text for a float-valued JSON number.
inline std::string num(double v) {
  char buf[64];
  std::snprintf(buf, sizeof buf, "%.9g", v);
  return buf;
}
inline std::string vec(double x, double y, double z) {
  return "[" + num(x) + ", " + num(y) + ", " + num(z) + "]";
}

// Either the loader refuses the scene with an InputError (a range check), or it
// renders a sane image: whichever the loader does, nothing in between.
inline void expectRefusedOrSane(const std::function<RenderResult()>& render, double maxRadiance,
                                const std::string& what) {
  try {
    RenderResult r = render();
    expectSane(r, maxRadiance, what);
  } catch (const InputError& e) {
    SUCCEED() << what << ": refused: " << e.what();
    std::printf("%s: refused by the loader: %s\n", what.c_str(), e.what());
  }
}

// A small open-front room (floor, ceiling, back and side walls of albedo <= 0.73)
// lit by a ceiling panel of radiance kRoomRadiance, with the caller's objects and
// materials added ("glass", "mirror", "white", "red", "green" exist). The camera is a
// little off the room's axis, so no pixel centre lies exactly on a shared edge (where
// the face a ray meets is a coin toss; hard_scale.cpp aims at those on purpose). Physical: no
// pixel can exceed the panel's radiance (radiance is conserved along rays, surfaces
// reflect at most what they receive, Fresnel splits add to 1), and the camera sees
// the panel at exactly that.
constexpr double kRoomRadiance = 15.0;
inline std::string roomJson(const std::string& model, const std::string& objects,
                            const std::string& materials = "", const std::string& render = "",
                            const std::string& photons = "") {
  return R"({
  "camera": {"position": [0.07, 1.03, 3.2], "look_at": [0.02, 0.98, 0], "fov": 55, "width": 48, "height": 48},
  "lights": [{"type": "quad", "corner": [-0.3, 1.98, -0.3], "edge1": [0.6, 0, 0], "edge2": [0, 0, 0.6],
              "radiance": 15}],
  "materials": {
    "white": {"diffuse": 0.73}, "red": {"diffuse": [0.63, 0.065, 0.05]},
    "green": {"diffuse": [0.14, 0.45, 0.091]},
    "mirror": {"ambient": 0, "diffuse": 0, "reflective": {"kr": 1}},
    "glass": {"ambient": 0, "diffuse": 0, "transparent": {"ior": 1.5}})" + materials + R"(
  },
  "objects": [
    {"type": "quad", "material": "white", "corner": [-1, 0, 1], "edge1": [2, 0, 0], "edge2": [0, 0, -2]},
    {"type": "quad", "material": "white", "corner": [-1, 2, -1], "edge1": [2, 0, 0], "edge2": [0, 0, 2]},
    {"type": "quad", "material": "white", "corner": [-1, 0, -1], "edge1": [2, 0, 0], "edge2": [0, 2, 0]},
    {"type": "quad", "material": "red", "corner": [-1, 0, 1], "edge1": [0, 0, -2], "edge2": [0, 2, 0]},
    {"type": "quad", "material": "green", "corner": [1, 0, -1], "edge1": [0, 0, 2], "edge2": [0, 2, 0]})" +
         objects + R"(
  ],
  "render": {"model": ")" + model + R"(", "max_depth": 8, "light_samples": 4)" + render + R"(},
  "photons": {"gate": "off", "shadow": 0, "global": 20000, "caustic": 20000, "k_global": 50,
              "k_caustic": 30, "max_bounces": 8)" + photons + R"(}
})";
}

// The classic room's bound: ambient 0.1 plus k_d (<= 0.73) times a panel sample's
// incidence L A cos cos / r^2 <= L A / d^2 (A = 0.36, d >= 0.6 from the panel to any
// surface it faces) per surface; mirror and glass pass at most the sum of their
// children, so a tree of depth D is <= (D + 1) x that; the panel itself is L.
inline double classicRoomBound(int maxDepth = 8) {
  return std::max(kRoomRadiance, (maxDepth + 1) * (0.1 + 0.73 * kRoomRadiance * 0.36 / 0.36));
}
inline double roomBound(const std::string& model, int maxDepth = 8) {
  return model == "physical" ? kRoomRadiance * (1 + 1e-5) : classicRoomBound(maxDepth);
}

// The room lit by a point light instead (an override): classic renders are then free
// of sampling noise, so two of them can be compared pixel by pixel. A quad light's
// samples are seeded per shading point, and a glass hit takes a shading point.
inline const std::string kRoomPointLight =
    R"(lights=[{"type": "point", "position": [0.1, 1.7, 0.3], "intensity": 2}])";
// Classic: (D + 1) x (ambient 0.1 + k_d I / d^2), d = 0.3 from the light to the ceiling.
inline double classicPointRoomBound(int maxDepth = 8) {
  return (maxDepth + 1) * (0.1 + 0.73 * 2 / (0.3 * 0.3));
}

}  // namespace penumbra::hard
