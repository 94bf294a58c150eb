// Progressive passes do not creep: in a closed Lambert sphere around a point light
// (uniform indirect radiance, known in closed form) the running mean of the passes,
// whose k shrinks with the schedule, stays with fixed-k passes over the same photons
// from the first pass on, through the precomputed irradiance cache.
#include "plan/pipeline.h"
#include "plan/render_session.h"
#include "support/furnace_scene.h"
#include "support/scratch_dir.h"
#include <gtest/gtest.h>
#include <fstream>
#include <string>
#include <vector>

namespace penumbra {
namespace {

// The furnace at k_global 24: the schedule gathers 24 down to 13 photons over 8
// passes, the k at which cells centred on their photons' centroid read +10%.
const std::vector<std::string> kSettings = {
    "camera.width=32", "camera.height=24", "photons.shadow=0", "photons.gate=false",
    "photons.global=300000", "photons.k_global=24", "photons.lookup=precomputed", "photons.passes=8"};

// The mean of the indirect view after each pass.
std::vector<double> runningMeans(const std::string& scene, const std::vector<std::string>& overrides) {
  SessionOptions options;
  options.threads = 2;
  RenderSession session(options);
  JobRequest request;
  request.scenePath = scene;
  request.overrides = overrides;
  request.view = "indirect";
  PlannedJob job = session.plan(request);
  session.prepare(job);
  std::vector<double> means;
  session.frame(job, session.photons(job), {}, [&](int passes, const Image& sum, const ErrorEstimate&) {
    double total = 0.0;
    for (const Color& c : sum.pixels) total += double(c.r) + c.g + c.b;
    means.push_back(total / (3.0 * double(sum.pixels.size()) * passes));
  });
  return means;
}

TEST(NoCreep, ShrinkingKStaysWithFixedKOverTheSamePhotonsAndTheClosedForm) {
  // Fixed k (alpha 1) is unbiased on this uniform density at any k: its passes, over
  // the same photons (streams keyed by seed and pass), are the converged value with
  // the photons' own noise (~0.5% a pass here) taken out of the comparison.
  const testing::ScratchDir scratch;
  const std::string file = (scratch.path() / "furnace.json").string();
  std::ofstream(file) << testing::kFurnace;
  const double kPiD = 3.14159265358979323846, e0 = 2.0 / (1.5 * 1.5), rho = 0.5;
  const double closedForm = rho / kPiD * e0 * rho / (1.0 - rho);
  for (const char* seed : {"render.seed=1", "render.seed=2"}) {
    std::vector<std::string> overrides = kSettings;
    overrides.push_back(seed);
    const std::vector<double> shrinking = runningMeans(file, overrides);
    overrides.push_back("photons.alpha=1");
    const std::vector<double> fixed = runningMeans(file, overrides);
    ASSERT_EQ(shrinking.size(), 8u);
    ASSERT_EQ(fixed.size(), 8u);
    EXPECT_DOUBLE_EQ(shrinking[0], fixed[0]) << seed;  // pass 1 gathers the same k
    for (size_t p = 0; p < shrinking.size(); ++p)
      EXPECT_NEAR(shrinking[p] / fixed[p], 1.0, 0.005) << seed << ", " << p + 1 << " passes";
    // Against the closed form, as test_physical_render.cpp's furnace: 2.4M photons'
    // noise (~0.15%) and a small positive offset on this sphere that does not depend
    // on the passes (+0.2% exact at k 100, up to +1.1% cached at k 24).
    EXPECT_NEAR(fixed.back() / closedForm, 1.0, 0.015) << seed;
    EXPECT_NEAR(shrinking.back() / closedForm, 1.0, 0.015) << seed;
  }
}

}  // namespace
}  // namespace penumbra
