// Progressive passes continue the camera's sample sequence: pass p draws points
// p x spp .. (p + 1) x spp - 1 of the pixel's (0,2)-sequence, so spp 1 with 16 passes
// antialiases as spp 16 in one pass (a slanted edge's pixels hold its covered share,
// not the pixel centre's verdict), and a pass's samples do not depend on how many
// passes follow.
#include "plan/pipeline.h"
#include "io/scene_loader.h"
#include "trace/camera.h"
#include "support/render_fixtures.h"
#include "support/scratch_dir.h"
#include "support/render_file.h"
#include <gtest/gtest.h>
#include <algorithm>
#include <cstdio>
#include <cstring>
#include <cmath>
#include <fstream>
#include <string>
#include <vector>

namespace penumbra {
namespace {

namespace fs = std::filesystem;

const std::string kScenes = std::string(PENUMBRA_SOURCE_DIR) + "/scenes";

double rmse(const Image& a, const Image& b) {
  double squares = 0.0;
  for (size_t i = 0; i < a.pixels.size(); ++i) {
    for (int c = 0; c < 3; ++c) squares += std::pow(double(a.pixels[i][c]) - b.pixels[i][c], 2);
  }
  return std::sqrt(squares / (3.0 * a.pixels.size()));
}

RenderResult render(const std::string& path, std::vector<std::string> overrides, const std::string& aov = "") {
  return testing::renderFile(path, std::move(overrides), 2, aov);
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

// Edge pixels (partly covered) against their covered share: their RMS, the mean of
// their error, their count; pixels wholly in or out must be exact.
struct EdgeError {
  double rms = 0.0, mean = 0.0;
  int count = 0;
};
EdgeError edgeError(const Image& image, const std::vector<double>& shares) {
  EdgeError e;
  double squares = 0.0, sum = 0.0;
  for (size_t i = 0; i < image.pixels.size(); ++i) {
    if (shares[i] == 0.0 || shares[i] == 1.0) {
      EXPECT_NEAR(image.pixels[i].r, shares[i] * kL0, 1e-4 * kL0) << "pixel " << i;  // wholly out or in
      continue;
    }
    const double d = image.pixels[i].r / kL0 - shares[i];
    squares += d * d;
    sum += d;
    ++e.count;
  }
  e.rms = std::sqrt(squares / std::max(1, e.count));
  e.mean = sum / std::max(1, e.count);
  return e;
}

TEST(Passes, SixteenPassesAtOneSppAntialiasAsSixteenSpp) {
  const testing::ScratchDir scratch;
  const std::string file = (scratch.path() / "edge.json").string();
  std::ofstream(file) << kEdge;
  const Image passes = render(file, {"photons.passes=16"}).image;
  const Image spp = render(file, {"camera.spp=16"}).image;
  const RenderResult one = render(file, {});
  const Image& centre = one.image;
  const CameraRays camera(loadScene(file).camera);
  std::vector<double> shares;
  for (int y = 0; y < spp.height; ++y) {
    for (int x = 0; x < spp.width; ++x) shares.push_back(coverage(camera, x, y));
  }

  // 16 spp jitters one sample in each cell of a 4 x 4 grid; 16 passes take 16 points
  // of a (0,2)-sequence, also one in each such cell. Either way only the <= 7 cells the
  // edge crosses are random, each a coin of weight 1/16: a pixel's error has sd <=
  // sqrt(7 / 4) / 16 = 0.083, so the RMS over the edge stays below 0.1, the mean error
  // within 3 sd / sqrt(edge pixels), and the two images' difference has sd <= 0.118.
  // The pixel centre alone is 0 or 1: RMS ~0.3 over an edge.
  const EdgeError p = edgeError(passes, shares), s = edgeError(spp, shares), c = edgeError(centre, shares);
  ASSERT_GE(s.count, 32);  // the edge crosses every row
  double squares = 0.0;
  for (size_t i = 0; i < shares.size(); ++i) {
    const double d = (passes.pixels[i].r - spp.pixels[i].r) / kL0;
    squares += d * d;
  }
  const double between = std::sqrt(squares / s.count);
  for (const EdgeError* e : {&p, &s}) {
    EXPECT_LT(e->rms, 0.1);
    EXPECT_NEAR(e->mean, 0.0, 3.0 * 0.083 / std::sqrt(double(e->count)));
  }
  EXPECT_LT(between, 0.118);
  EXPECT_GT(c.rms, 0.2) << "the pixel centre should not antialias";
  // The centres' own estimate (probes beside them) against their exact error: the
  // image's RMSE from the covered shares (grey, so every channel alike).
  const double exact = c.rms * kL0 * std::sqrt(double(c.count) / double(shares.size()));
  ASSERT_EQ(one.stats.error.source, ErrorSource::Probes);
  EXPECT_NEAR(one.stats.error.noiseRmse / exact, 1.0, 0.1) << one.stats.error.noiseRmse << " against " << exact;
  std::printf("%d edge pixels, RMS of the covered share: %.4f (16 passes at 1 spp), %.4f (16 spp), %.4f (1 pass "
              "at 1 spp); mean error %.4f, %.4f; RMS between the first two %.4f; the centres' estimate / exact %.3f\n",
              s.count, p.rms, s.rms, c.rms, p.mean, s.mean, between, one.stats.error.noiseRmse / exact);
}

TEST(Passes, APassSamplesTheSameWhateverPassesFollow) {
  // Pass p's camera samples come from the pixel's sequence at p x spp: the first 8
  // passes of 16 are the 8 passes of 8, byte for byte, so stopping early (or going on)
  // changes nothing before. Each differs from the pixel-centre image (one pass).
  const testing::ScratchDir scratch;
  const std::string file = (scratch.path() / "edge.json").string();
  std::ofstream(file) << kEdge;
  const Scene scene = loadScene(file);
  Rig rig(scene);
  const Image centre = rig.render();
  for (uint32_t pass = 0; pass < 8; ++pass) {
    rig.ctx.pass = pass;
    rig.ctx.passes = 8;
    const Image of8 = rig.render();
    rig.ctx.passes = 16;
    const Image of16 = rig.render();
    ASSERT_EQ(of8.pixels.size(), of16.pixels.size());
    EXPECT_EQ(std::memcmp(of8.pixels.data(), of16.pixels.data(), of8.pixels.size() * sizeof(Color)), 0) << pass;
    EXPECT_NE(std::memcmp(of8.pixels.data(), centre.pixels.data(), of8.pixels.size() * sizeof(Color)), 0) << pass;
  }
}

TEST(Passes, CornellDirectLightOfPassesIsSppsWithinSeedNoise) {
  // cornell_physical's direct view (shadow rays, mirror and glass paths, no photons):
  // 8 passes at 2 spp against one pass at 16 spp differ by the camera and light samples
  // only, as two seeds of 16 spp do.
  const std::string file = kScenes + "/cornell_physical.json";
  const std::vector<std::string> small = {"camera.width=48", "camera.height=48"};
  std::vector<std::string> passes = small, spp = small, seed = small;
  passes.insert(passes.end(), {"camera.spp=2", "photons.passes=8"});
  spp.insert(spp.end(), {"camera.spp=16", "photons.passes=1"});
  seed.insert(seed.end(), {"camera.spp=16", "photons.passes=1", "render.seed=9"});
  const Image a = render(file, passes, "direct").image, b = render(file, spp, "direct").image;
  const Image c = render(file, seed, "direct").image;
  const double between = rmse(a, b), noise = rmse(b, c);
  std::printf("direct view RMSE: 8 passes x 2 spp against 16 spp %.5f; two seeds of 16 spp %.5f\n", between, noise);
  EXPECT_GT(noise, 0.0);
  EXPECT_LT(between, 1.5 * noise);
}

}  // namespace
}  // namespace penumbra
