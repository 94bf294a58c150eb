// Whether a surface lit only by the global map creeps with progressive passes: the
// ceiling of an area-light room (scenes/cornell_physical.json with its point light
// replaced by a 0.5 m quad under the ceiling) in the indirect view, after 1, 2, 4, ...
// passes of one render, against the converged value: the mean of fixed-k passes
// (photons.alpha 1) over every seed. The figures of docs/photon-maps.md ("Progressive
// passes"):
//   build/bench/bench_creep [--photons 30000000] [--passes 64] [--fixed-passes 16]
//       [--seeds 1,2] [--lookup precomputed|exact] [--threads 2]
#include "bench/comma_list.h"
#include "plan/render_session.h"
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <string>
#include <vector>

namespace penumbra {
namespace {

constexpr int kSize = 160;
// The ceiling in front of the light, clear of the walls: x 30-129, y 0-17 of 160x160.
constexpr int kX0 = 30, kX1 = 130, kY0 = 0, kY1 = 18;

// The mean of the three channels over the ceiling patch of `sum`, divided by `passes`.
double patchMean(const Image& sum, int passes) {
  double total = 0.0;
  for (int y = kY0; y < kY1; ++y)
    for (int x = kX0; x < kX1; ++x) total += double(sum.at(x, y).r) + sum.at(x, y).g + sum.at(x, y).b;
  return total / (3.0 * (kX1 - kX0) * (kY1 - kY0) * passes);
}

// The patch's running mean after each pass of one render.
std::vector<double> runningMeans(const std::vector<std::string>& overrides, int threads) {
  SessionOptions options;
  options.threads = threads;
  RenderSession session(options);
  JobRequest request;
  request.scenePath = std::string(PENUMBRA_SOURCE_DIR) + "/scenes/cornell_physical.json";
  request.overrides = overrides;
  request.view = "indirect";
  PlannedJob job = session.plan(request);
  session.prepare(job);
  std::vector<double> means;
  session.frame(job, session.photons(job), {},
                [&](int passes, const Image& sum, const ErrorEstimate&) { means.push_back(patchMean(sum, passes)); });
  return means;
}

// The standard deviation of one pass's patch mean, from the passes' own means.
double passSpread(const std::vector<double>& running) {
  std::vector<double> pass(running.size());
  for (size_t p = 0; p < running.size(); ++p)
    pass[p] = running[p] * double(p + 1) - (p > 0 ? running[p - 1] * double(p) : 0.0);
  double mean = 0.0, squares = 0.0;
  for (double v : pass) mean += v / double(pass.size());
  for (double v : pass) squares += (v - mean) * (v - mean);
  return std::sqrt(squares / double(pass.size() - 1));
}

int run(int argc, char** argv) {
  long photons = 30000000;
  int passes = 64, fixedPasses = 16, threads = 2;
  std::string lookup = "precomputed";
  std::vector<std::string> seeds = {"1", "2"};
  for (int i = 1; i < argc; ++i) {
    const std::string a = argv[i];
    if (a == "--photons" && i + 1 < argc) photons = std::atol(argv[++i]);
    else if (a == "--passes" && i + 1 < argc) passes = std::atoi(argv[++i]);
    else if (a == "--fixed-passes" && i + 1 < argc) fixedPasses = std::atoi(argv[++i]);
    else if (a == "--threads" && i + 1 < argc) threads = std::atoi(argv[++i]);
    else if (a == "--lookup" && i + 1 < argc) lookup = argv[++i];
    else if (a == "--seeds" && i + 1 < argc) seeds = bench::commaList(argv[++i]);
    else {
      std::fprintf(stderr, "bench_creep: unknown argument '%s'\n", a.c_str());
      return 2;
    }
  }
  if (fixedPasses < 2 || passes < 1) {
    std::fprintf(stderr,
                 "bench_creep: --fixed-passes needs 2 or more (their spread is the noise), --passes 1 or more\n");
    return 2;
  }
  const std::vector<std::string> room = {
      R"(lights[0]={"type":"quad","corner":[-0.25,1.98,-0.25],"edge1":[0.5,0,0],"edge2":[0,0,0.5],"color":[1,1,1],"power":20})",
      "camera.width=" + std::to_string(kSize),
      "camera.height=" + std::to_string(kSize),
      "photons.caustic=1000",
      "photons.lookup=" + lookup,
      "photons.global=" + std::to_string(photons)};

  // Per seed: the shipped schedule and fixed k over the same photons (streams keyed by
  // seed and pass), so their ratio has the photons' noise taken out.
  std::vector<std::vector<double>> shrinking, fixed;
  double converged = 0.0, spread = 0.0;
  for (const std::string& seed : seeds) {
    std::vector<std::string> overrides = room;
    overrides.push_back("render.seed=" + seed);
    overrides.push_back("photons.passes=" + std::to_string(passes));
    shrinking.push_back(runningMeans(overrides, threads));
    overrides.back() = "photons.passes=" + std::to_string(fixedPasses);
    overrides.push_back("photons.alpha=1");
    fixed.push_back(runningMeans(overrides, threads));
    converged += fixed.back().back() / double(seeds.size());
    spread += passSpread(fixed.back()) / double(seeds.size());
  }
  std::printf("%ld global photons a pass, lookup %s; converged (fixed k, %d passes x %zu seeds): %.5f\n", photons,
              lookup.c_str(), fixedPasses, seeds.size(), converged);
  std::printf("one pass's noise: %.3f%% (the spread of fixed-k passes); the converged value's: %.3f%%\n",
              100.0 * spread / converged, 100.0 * spread / converged / std::sqrt(double(fixedPasses * seeds.size())));
  std::printf("%6s", "passes");
  for (const std::string& seed : seeds) std::printf("  seed %s: mean, vs converged, vs fixed k", seed.c_str());
  std::printf("  noise of the mean\n");
  for (int p = 1; p <= passes; p *= 2) {
    std::printf("%6d", p);
    for (size_t s = 0; s < seeds.size(); ++s) {
      const double m = shrinking[s][p - 1];
      std::printf("  %8.5f %+8.3f%%", m, 100.0 * (m / converged - 1.0));
      if (p <= fixedPasses) std::printf(" %+8.3f%%", 100.0 * (m / fixed[s][p - 1] - 1.0));
      else std::printf(" %9s", "-");
    }
    std::printf("  %8.3f%%\n", 100.0 * spread / converged / std::sqrt(double(p)));
  }
  return 0;
}

}  // namespace
}  // namespace penumbra

int main(int argc, char** argv) { return penumbra::run(argc, argv); }
