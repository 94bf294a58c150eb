// Probes of a one-sample image: pixels picked by contrast, two jittered grids each,
// the centre's squared error estimated without bias and summed over the picks.
#include "trace/probe_error.h"
#include "core/rng.h"
#include "trace/camera.h"
#include "trace/render.h"
#include <tbb/enumerable_thread_specific.h>
#include <tbb/parallel_for.h>
#include <algorithm>
#include <cmath>
#include <vector>

namespace penumbra {

namespace {

// The probes' random streams: sample indices no frame reaches (passes x spp < 2^32).
constexpr uint64_t kProbeStream = uint64_t(1) << 40;
// A pixel's share of the probes: its largest channel difference to a neighbour,
// squared (an edge of contrast D leaves its centre ~D^2 off), plus a floor of this
// share of the mean so flat pixels (shading noise alone) are picked too.
constexpr double kFlatShare = 0.1;

double contrastWeight(const Image& image, const PixelBounds& b, int x, int y) {
  const int w = image.width;
  const Color& c = image.pixels[size_t(y) * w + x];
  float most = 0.0f;
  for (int dy = -1; dy <= 1; ++dy)
    for (int dx = -1; dx <= 1; ++dx) {
      const int xx = std::clamp(x + dx, b.x0, b.x1 - 1), yy = std::clamp(y + dy, b.y0, b.y1 - 1);
      most = std::max(most, maxComponent(glm::abs(image.pixels[size_t(yy) * w + xx] - c)));
    }
  return std::isfinite(most) ? double(most) * most : 0.0;
}

// The mean of one jittered m x m grid of samples in pixel (x, y), false if none was finite.
bool gridMean(const ShadingContext& ctx, const CameraRays& camera, Aov aov, int x, int y, uint64_t pixel,
              int grid, int m, ThreadState& ts, glm::dvec3& mean) {
  const uint64_t seed = ctx.scene.render.seed;
  mean = glm::dvec3(0.0);
  int counted = 0;
  for (int j = 0; j < m * m; ++j) {
    const uint64_t key = hashKey(seed, pixel, kProbeStream + uint64_t(grid) * 64 + j);
    Rng rng(key);
    const float ox = (j % m + rng.uniform()) / m, oy = (j / m + rng.uniform()) / m;
    beginSample(ts, key);
    const Color c = shadeCameraRay(ctx, camera.generate(x + ox, y + oy, key), aov, ts);
    if (!isFinite(c)) continue;
    mean += glm::dvec3(c);
    ++counted;
  }
  if (counted == 0) return false;
  mean /= double(counted);
  return true;
}

}  // namespace

ErrorEstimate probeError(const ShadingContext& ctx, const Image& image, Aov aov, Image* perPixel,
                         const PixelBounds* bounds) {
  const int w = image.width, h = image.height;
  const PixelBounds area = bounds ? *bounds : PixelBounds::frame(w, h);
  const size_t n = area.pixels();
  // The weights' sum by rows, in row order (the figure must not depend on the threads);
  // each pixel's weight is read again when it is picked, so nothing per pixel is kept.
  std::vector<double> rowWeight(h, 0.0);
  tbb::parallel_for(area.y0, area.y1, [&](int y) {
    for (int x = area.x0; x < area.x1; ++x) rowWeight[y] += contrastWeight(image, area, x, y);
  });
  double sum = 0.0;
  for (double v : rowWeight) sum += v;
  const double floor = std::max(kFlatShare * sum / double(n), 1e-300);
  const double total = sum + floor * double(n);
  const double asked = std::min(double(n), std::max(double(kMinProbes), kProbeShare * double(n)));
  if (perPixel) *perPixel = Image(w, h);

  // Per row: the weighed sum of the estimates and the pixels probed (summed in row
  // order after, so the figure does not depend on the threads).
  std::vector<double> rowSum(h, 0.0);
  std::vector<int> rowProbes(h, 0);
  tbb::enumerable_thread_specific<ThreadState> states;
  const CameraRays camera(ctx.scene.camera);
  const uint64_t seed = ctx.scene.render.seed;
  tbb::parallel_for(area.y0, area.y1, [&](int y) {
    ThreadState& ts = states.local();
    for (int x = area.x0; x < area.x1; ++x) {
      const size_t i = size_t(y) * w + x;
      const double chance = std::min(1.0, asked * (contrastWeight(image, area, x, y) + floor) / total);
      Rng pick(hashKey(seed, i, kProbeStream));
      if (!perPixel && !(pick.uniform() < chance)) continue;
      const int m = chance >= 1.0 ? 4 : 2;
      glm::dvec3 a, b;
      if (!gridMean(ctx, camera, aov, x, y, i, 0, m, ts, a) || !gridMean(ctx, camera, aov, x, y, i, 1, m, ts, b))
        continue;
      const glm::dvec3 centre(image.pixels[i]);
      const glm::dvec3 d = (centre - a) * (centre - b);
      rowSum[y] += (d.x + d.y + d.z) / 3.0 / (perPixel ? 1.0 : chance);
      ++rowProbes[y];
      if (perPixel) perPixel->pixels[i] = Color(glm::sqrt(glm::max(d, glm::dvec3(0.0))));
    }
  });
  double mse = 0.0;
  int probed = 0;
  for (int y = 0; y < h; ++y) {
    mse += rowSum[y];
    probed += rowProbes[y];
  }
  ErrorEstimate e;
  e.source = ErrorSource::Probes;
  e.count = probed;
  e.noiseRmse = std::sqrt(std::max(0.0, mse / double(n)));
  // Probes that found no error (all centres agreed with their grids, or the estimates
  // summed to <= 0) prove none: the pixels they did not reach may hold some.
  e.lowerBound = !(mse > 0.0);
  return e;
}

}  // namespace penumbra
