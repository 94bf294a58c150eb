// Progressive passes continue the camera's sample sequence: pass p draws samples
// p x spp .. (p + 1) x spp - 1 of the frame's passes x spp, stratified over them all,
// so spp 1 with 16 passes antialiases exactly as spp 16 in one pass (same camera rays),
// and a slanted edge's pixels hold its covered share, not the pixel centre's verdict.
#include "plan/pipeline.h"
#include "io/scene_loader.h"
#include "trace/camera.h"
#include "support/scratch_dir.h"
#include <gtest/gtest.h>
#include <algorithm>
#include <cstdio>
#include <cmath>
#include <fstream>
#include <string>
#include <vector>

namespace penumbra {
namespace {

namespace fs = std::filesystem;

const std::string kScenes = std::string(PENUMBRA_SOURCE_DIR) + "/scenes";

RenderResult render(const std::string& path, std::vector<std::string> overrides, const std::string& aov = "") {
  RenderRequest req;
  req.scenePath = path;
  req.overrides = std::move(overrides);
  req.threads = 2;
  req.aov = aov;
  return runRender(req);
}

// Seen from above by an orthographic camera (32 x 32 pixels of 1/16): a Lambert quad
// (rho 0.5) whose left edge runs through (0.03, 0) tilted 17 degrees off the pixel
// columns, lit straight down by a directional light (E = 1), over a black background.
// Direct light only: no photons, so every pixel is L0 = rho E / pi times the share of
// its area the quad covers.
const char* kEdge = R"({
  "name": "slanted_edge",
  "camera": {"position": [0, 0, 5], "look_at": [0, 0, 0], "up": [0, 1, 0], "ortho_height": 2,
             "width": 32, "height": 32, "spp": 1},
  "lights": [{"type": "directional", "direction": [0, 0, -1], "intensity": 1}],
  "materials": {"white": {"diffuse": 0.5}},
  "objects": [{"type": "quad", "corner": [-1.431853, -4.781502, 0], "edge1": [4.781502, -1.461853, 0],
               "edge2": [2.923707, 9.563048, 0], "material": "white"}],
  "render": {"model": "physical", "seed": 5},
  "photons": {"gate": false, "global": 0, "caustic": 0}
})";

constexpr double kL0 = 0.5 / 3.14159265358979323846;

// The share of pixel (x, y) whose camera rays meet the quad's half-plane (x' >= the
// edge), by 128 x 128 points: within 1/128 of the true area for a straight edge.
double coverage(const CameraRays& camera, int x, int y) {
  const glm::dvec2 through(0.03, 0.0), normal(std::cos(0.2967), -std::sin(0.2967));  // 17 degrees
  constexpr int kGrid = 128;
  int inside = 0;
  for (int j = 0; j < kGrid; ++j) {
    for (int i = 0; i < kGrid; ++i) {
      const Ray r = camera.generate(x + (i + 0.5f) / kGrid, y + (j + 0.5f) / kGrid);
      const glm::dvec2 p(r.origin.x, r.origin.y);  // rays run along -z
      inside += glm::dot(p - through, normal) >= 0.0;
    }
  }
  return double(inside) / (kGrid * kGrid);
}

TEST(Passes, SixteenPassesAtOneSppAntialiasAsSixteenSpp) {
  const testing::ScratchDir scratch;
  const std::string file = (scratch.path() / "edge.json").string();
  std::ofstream(file) << kEdge;
  const Image passes = render(file, {"photons.passes=16"}).image;
  const Image spp = render(file, {"camera.spp=16"}).image;
  const Image centre = render(file, {}).image;
  ASSERT_EQ(passes.pixels.size(), spp.pixels.size());

  // The same camera rays, the same light: equal but for the float mean of 16 pass
  // images against spp's double sum (a few ulps).
  for (size_t i = 0; i < spp.pixels.size(); ++i) {
    ASSERT_NEAR(passes.pixels[i].r, spp.pixels[i].r, 1e-6) << "pixel " << i;
  }

  // Edge pixels (partly covered) against their covered share. Jittered 4 x 4 strata:
  // only the <= 7 strata the edge crosses are random, each a coin of weight 1/16, so a
  // pixel's error has sd <= sqrt(7 / 4) / 16 = 0.083 and the RMS over the edge stays
  // below 0.1; their mean error is within 3 sd / sqrt(edge pixels). The pixel centre
  // alone is 0 or 1: RMS ~0.3 over an edge.
  const CameraRays camera(loadScene(file).camera);
  double squares = 0.0, centreSquares = 0.0, sum = 0.0;
  int edge = 0;
  for (int y = 0; y < spp.height; ++y) {
    for (int x = 0; x < spp.width; ++x) {
      const double share = coverage(camera, x, y);
      if (share == 0.0 || share == 1.0) {
        EXPECT_NEAR(spp.at(x, y).r, share * kL0, 1e-4 * kL0) << x << "," << y;  // wholly out or in
        continue;
      }
      const double e = spp.at(x, y).r / kL0 - share, c = centre.at(x, y).r / kL0 - share;
      squares += e * e;
      centreSquares += c * c;
      sum += e;
      ++edge;
    }
  }
  ASSERT_GE(edge, 32);  // the edge crosses every row
  const double rms = std::sqrt(squares / edge), centreRms = std::sqrt(centreSquares / edge);
  EXPECT_LT(rms, 0.1);
  EXPECT_NEAR(sum / edge, 0.0, 3.0 * 0.083 / std::sqrt(double(edge)));
  EXPECT_GT(centreRms, 0.2) << "the pixel centre should not antialias";
  std::printf("edge pixels %d: RMS of the covered share %.4f (16 passes or 16 spp), %.4f (1 pass at 1 spp)\n", edge,
              rms, centreRms);
}

TEST(Passes, CornellDirectLightIsTheSameForPassesAsForSpp) {
  // cornell_physical's direct view (shadow rays, mirror and glass paths, no photons):
  // 8 passes at 2 spp and one pass at 16 spp trace the same camera rays and draw the
  // same light samples, so they differ by float rounding of the mean only.
  const std::string file = kScenes + "/cornell_physical.json";
  const std::vector<std::string> small = {"camera.width=48", "camera.height=48"};
  std::vector<std::string> passes = small, spp = small;
  passes.insert(passes.end(), {"camera.spp=2", "photons.passes=8"});
  spp.insert(spp.end(), {"camera.spp=16"});
  const Image a = render(file, passes, "direct").image, b = render(file, spp, "direct").image;
  ASSERT_EQ(a.pixels.size(), b.pixels.size());
  for (size_t i = 0; i < a.pixels.size(); ++i) {
    for (int c = 0; c < 3; ++c) {
      ASSERT_NEAR(a.pixels[i][c], b.pixels[i][c], 1e-5 * std::max(1.0f, b.pixels[i][c])) << "pixel " << i;
    }
  }
}

}  // namespace
}  // namespace penumbra
