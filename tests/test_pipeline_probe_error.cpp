// The probes' estimate of a one-sample image's error against that error measured:
// unbiased where the error is shading noise alone (one sample of an area light, the
// estimate within 5% of the RMSE against 256 samples, where a probe's grids read
// as one would be 13% high), and deterministic for any thread count.
#include "core/error_estimate.h"
#include "plan/pipeline.h"
#include "support/scratch_dir.h"
#include "support/render_file.h"
#include <gtest/gtest.h>
#include <cmath>
#include <cstdio>

using namespace penumbra;

namespace {

// A diffuse floor filling the view, lit from beside it by a quad light drawn once per
// shading point:
// every pixel is noise about a smooth mean, and no edge is in the frame.
const char* kNoisyFloor = R"({
  "name": "noisy_floor",
  "camera": {"position": [0, 0, 4], "look_at": [0, 0, 0], "up": [0, 1, 0], "ortho_height": 2,
             "width": 64, "height": 64, "spp": 1},
  "lights": [{"type": "quad", "corner": [1.5, -0.5, 1], "edge1": [0, 1, 0], "edge2": [1, 0, 0], "radiance": 2}],
  "materials": {"floor": {"diffuse": 0.6}},
  "objects": [{"type": "quad", "corner": [-3, -3, 0], "edge1": [6, 0, 0], "edge2": [0, 6, 0], "material": "floor"}],
  "render": {"model": "physical", "light_samples": 1, "seed": 3},
  "photons": {"gate": false, "global": 0, "caustic": 0}
})";

using penumbra::testing::renderFile;

double rmse(const Image& a, const Image& b) {
  double squares = 0.0;
  for (size_t i = 0; i < a.pixels.size(); ++i)
    for (int c = 0; c < 3; ++c) squares += std::pow(double(a.pixels[i][c]) - b.pixels[i][c], 2);
  return std::sqrt(squares / (3.0 * a.pixels.size()));
}

TEST(ProbeError, ShadingNoiseIsEstimatedWithoutBias) {
  const penumbra::testing::ScratchDir dir;
  const std::string file = dir.write("floor.json", kNoisyFloor).string();
  const RenderResult one = renderFile(file, {}, 2);
  const RenderResult reference = renderFile(file, {"camera.spp=256"}, 2);
  ASSERT_EQ(one.stats.error.source, ErrorSource::Probes);
  // Every pixel probed (the error view's estimate): 4096 probes put the figure's own
  // scatter near 1%, so 5% tells an unbiased estimate from one 13% high.
  const RenderResult view = renderFile(file, {}, 2, "error");
  ASSERT_EQ(view.stats.error.count, 64 * 64);
  const double measured = rmse(one.image, reference.image);
  std::printf("noisy floor: RMSE %.5f against 256 spp; estimate %.5f (every pixel), %.5f (%d probed)\n", measured,
              view.stats.error.noiseRmse, one.stats.error.noiseRmse, one.stats.error.count);
  EXPECT_NEAR(view.stats.error.noiseRmse / measured, 1.0, 0.05);
  EXPECT_NEAR(one.stats.error.noiseRmse / measured, 1.0, 0.10);  // weighed by the inverse chance
}

TEST(ProbeError, TheEstimateDoesNotDependOnTheThreads) {
  const penumbra::testing::ScratchDir dir;
  const std::string file = dir.write("floor.json", kNoisyFloor).string();
  const ErrorEstimate a = renderFile(file, {}, 1).stats.error, b = renderFile(file, {}, 2).stats.error;
  EXPECT_EQ(a.count, b.count);
  EXPECT_EQ(a.noiseRmse, b.noiseRmse);
}

}  // namespace
