// Adaptive pixel sampling against uniform sampling on one scene: CPU seconds, camera
// samples, RMSE against a converged reference (the render box-filtered to its
// resolution), RMSE at full resolution against the mean of two longer renders less
// that mean's own noise, and the error estimate against the noise measured between
// two seeds. The figures of docs/accuracy.md ("Adaptive pixel sampling"):
//   build/bench/bench_adaptive [--scene S] [--reference R.exr] [--full-reference A.exr,B.exr]
//       [--threads 2] [--seeds 1,2] LABEL=KEY=VALUE,KEY=VALUE ...
// e.g. uniform=render.adaptive=false adaptive=render.adaptive=true
#include "bench/comma_list.h"
#include "io/image_io.h"
#include "plan/pipeline.h"
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <string>
#include <vector>

namespace penumbra {
namespace {

// The mean of each scale x scale block.
Image boxFilter(const Image& image, int scale) {
  Image out(image.width / scale, image.height / scale);
  for (int y = 0; y < out.height * scale; ++y) {
    for (int x = 0; x < out.width * scale; ++x) {
      out.pixels[size_t(y / scale) * out.width + x / scale] += image.at(x, y) / float(scale * scale);
    }
  }
  return out;
}

// RMSE over pixels and channels (a scaled by `scale` first: the weights of a difference).
double rmse(const Image& a, const Image& b, double scale = 1.0) {
  double squares = 0.0;
  for (size_t i = 0; i < a.pixels.size(); ++i) {
    for (int c = 0; c < 3; ++c) squares += std::pow(scale * (double(a.pixels[i][c]) - b.pixels[i][c]), 2);
  }
  return std::sqrt(squares / (3.0 * double(a.pixels.size())));
}

int run(int argc, char** argv) {
  std::string scene = std::string(PENUMBRA_SOURCE_DIR) + "/scenes/cornell_physical.json";
  std::string reference = std::string(PENUMBRA_SOURCE_DIR) + "/tests/data/reference/cornell_physical_converged.exr";
  int threads = 2;
  std::vector<std::string> seeds = {"1", "2"}, full;
  std::vector<std::pair<std::string, std::vector<std::string>>> configs;
  for (int i = 1; i < argc; ++i) {
    const std::string a = argv[i];
    if (a == "--scene" && i + 1 < argc) scene = argv[++i];
    else if (a == "--reference" && i + 1 < argc) reference = argv[++i];
    else if (a == "--full-reference" && i + 1 < argc) full = bench::commaList(argv[++i]);
    else if (a == "--threads" && i + 1 < argc) threads = std::atoi(argv[++i]);
    else if (a == "--seeds" && i + 1 < argc) seeds = bench::commaList(argv[++i]);
    else if (a.find('=') != std::string::npos)
      configs.push_back({a.substr(0, a.find('=')), bench::commaList(a.substr(a.find('=') + 1))});
    else {
      std::fprintf(stderr, "bench_adaptive: unknown argument '%s'\n", a.c_str());
      return 2;
    }
  }
  const Image ref = readImage(reference);
  // Two longer renders of other seeds: their mean, and its own noise (half their
  // difference's RMS), which adds in quadrature to every figure against it.
  Image fullRef;
  double fullNoise = 0.0;
  if (full.size() == 2) {
    const Image a = readImage(full[0]), b = readImage(full[1]);
    fullRef = a;
    for (size_t i = 0; i < a.pixels.size(); ++i) fullRef.pixels[i] = 0.5f * (a.pixels[i] + b.pixels[i]);
    fullNoise = rmse(a, b, 0.5);
    std::printf("full-resolution reference: its own noise %.5f\n", fullNoise);
  }
  std::printf("%-16s %6s %11s %9s %9s %9s %9s %9s %9s %7s\n", "config", "CPU s", "camera rays", "RMSE ref", "RMSE full",
              "less ref", "estimate", "noise", "noise ref", "est/noi");
  for (const auto& [label, overrides] : configs) {
    double cpu = 0.0, error = 0.0, estimate = 0.0, fullError = 0.0;
    uint64_t rays = 0;
    std::vector<Image> images;
    for (const std::string& seed : seeds) {
      RenderRequest req;
      req.scenePath = scene;
      req.overrides = overrides;
      req.overrides.push_back("render.seed=" + seed);
      req.session.threads = threads;
      const RenderResult r = runRender(req);
      cpu += r.stats.cpu.cpuSeconds;
      rays += r.stats.rays.camera;
      estimate += r.stats.error.noiseRmse;
      error += rmse(boxFilter(r.image, r.image.width / ref.width), ref);
      if (!fullRef.pixels.empty()) fullError += rmse(r.image, fullRef);
      std::fprintf(stderr, "%s seed %s: RMSE %.5f, estimate %.5f, %.1f CPU s\n", label.c_str(), seed.c_str(),
                   rmse(boxFilter(r.image, r.image.width / ref.width), ref), r.stats.error.noiseRmse,
                   r.stats.cpu.cpuSeconds);
      images.push_back(r.image);
    }
    const double n = double(seeds.size());
    // Two seeds' difference has twice one render's variance.
    const int scale = images[0].width / ref.width;
    const double noise = images.size() >= 2 ? rmse(images[0], images[1], std::sqrt(0.5)) : -1.0;
    const double noiseRef = images.size() >= 2
                                ? rmse(boxFilter(images[0], scale), boxFilter(images[1], scale), std::sqrt(0.5))
                                : -1.0;
    fullError /= n;
    std::printf("%-16s %6.1f %11llu %9.5f %9.5f %9.5f %9.5f %9.5f %9.5f %7.3f\n", label.c_str(), cpu / n,
                static_cast<unsigned long long>(rays / seeds.size()), error / n, fullError,
                std::sqrt(std::max(0.0, fullError * fullError - fullNoise * fullNoise)), estimate / n, noise, noiseRef,
                noise > 0 ? estimate / n / noise : 0.0);
    std::fflush(stdout);
  }
  return 0;
}

}  // namespace
}  // namespace penumbra

int main(int argc, char** argv) { return penumbra::run(argc, argv); }
