// The noise RMSE of the mean image from its even and odd passes' means, and the
// first-half/second-half bias check at 2, 4, 8, ... passes.
#include "core/error_estimate.h"
#include <fmt/format.h>
#include <algorithm>
#include <cmath>
#include <utility>

namespace penumbra {
namespace {

// Sum over pixels and channels of a per-pixel quantity, in double, in pixel order.
template <class F>
double sumOver(const Image& like, F perChannel) {
  double sum = 0.0;
  for (size_t i = 0; i < like.pixels.size(); ++i) {
    for (int c = 0; c < 3; ++c) sum += perChannel(i, c);
  }
  return sum;
}

// Its mean over `values` pixel channels.
double meanOf(double sum, size_t values) { return values == 0 ? 0.0 : sum / double(values); }

// The variance of the mean of `passes` passes at one pixel channel, from the sums of
// the even and of the odd passes.
double varianceOfMean(const Image& even, const Image& odd, int passes, size_t i, int c) {
  const double ne = (passes + 1) / 2, no = passes / 2;
  const double d = double(even.pixels[i][c]) / ne - double(odd.pixels[i][c]) / no;
  return ne * no / (double(passes) * passes) * d * d;
}

// Passes 1..h against h+1..2h: their difference's mean square, less what noise alone
// gives it (each half's mean has twice the variance of the whole's), is the bias that
// changed.
double biasOf(double squareSum, double noiseSum, size_t values) {
  return std::sqrt(std::max(0.0, meanOf(squareSum, values) - 4.0 * meanOf(noiseSum, values)));
}

}  // namespace

std::string describeError(const ErrorEstimate& e) {
  if (!e.known()) return "unknown (nothing was rendered that reads light)";
  const char* shared = e.sharedMaps ? "; probes share the photon map, so its noise is not in it" : "";
  if (e.source == ErrorSource::Probes && e.lowerBound) {
    return fmt::format("at least {:.3g} RMSE (noise and aliasing of the pixel centres: probes at {} pixels found none, "
                       "pixels they missed may hold some; --aov error probes every pixel){}",
                       e.noiseRmse, e.count, shared);
  }
  if (e.source == ErrorSource::Probes) {
    return fmt::format("~{:.3g} RMSE (noise and aliasing of the pixel centres, from probes at {} pixels){}",
                       e.noiseRmse, e.count, shared);
  }
  std::string out = fmt::format("~{:.3g} RMSE (noise, from {} {})", e.noiseRmse, e.count,
                                e.source == ErrorSource::Passes ? "passes" : "samples per pixel");
  if (e.source == ErrorSource::Samples && e.sharedMaps) out += "; samples share one photon map, so its noise is not in it";
  if (e.biasRmse < 0.0) return out;
  const std::string halves = e.biasHalf == 1 ? "passes 1 and 2"
                                             : fmt::format("passes 1-{} and {}-{}", e.biasHalf, e.biasHalf + 1,
                                                           2 * e.biasHalf);
  out += e.biasRmse > 0.0 ? fmt::format("; photon-map bias: {} differ by ~{:.3g} RMSE beyond noise", halves, e.biasRmse)
                          : fmt::format("; photon-map bias: {} agree within noise", halves);
  return out;
}

void PassSpread::add(const Image& sumBefore, const Image& image, int pass) {
  Image& half = pass % 2 == 0 ? even_ : odd_;
  if (half.pixels.empty()) half = image;
  else for (size_t i = 0; i < image.pixels.size(); ++i) half.pixels[i] += image.pixels[i];
  passes_ = pass + 1;
  if (pass == 0) {
    snapshot_ = image;
    snapshotPasses_ = 1;
    return;
  }
  if (passes_ != 2 * snapshotPasses_) return;
  biasSums(snapshot_, sumBefore, image, even_, odd_, passes_, snapshotPasses_, biasSquareSum_, biasNoiseSum_);
  biasHalf_ = snapshotPasses_;
  if (keep_) checkpoint_ = {snapshot_, sumBefore, image, even_, odd_, passes_, snapshotPasses_};
  for (size_t i = 0; i < image.pixels.size(); ++i) snapshot_.pixels[i] = sumBefore.pixels[i] + image.pixels[i];
  snapshotPasses_ = passes_;
}

void PassSpread::biasSums(const Image& first, const Image& before, const Image& pass, const Image& even,
                          const Image& odd, int passes, int half, double& squares, double& noise) {
  const double h = half;
  squares = sumOver(pass, [&](size_t i, int c) {
    const double a = first.pixels[i][c] / h;
    const double b = (double(before.pixels[i][c]) + pass.pixels[i][c] - first.pixels[i][c]) / h;
    return (a - b) * (a - b);
  });
  noise = sumOver(pass, [&](size_t i, int c) { return varianceOfMean(even, odd, passes, i, c); });
}

ErrorEstimate PassSpread::fromHalves(const Image& even, const Image& odd, int passes, const PassCheckpoint& cp) {
  double squares = 0.0, noise = 0.0;
  if (cp.half > 0) biasSums(cp.first, cp.before, cp.pass, cp.even, cp.odd, cp.passes, cp.half, squares, noise);
  return estimateFrom(even, odd, passes, squares, noise, cp.half);
}

ErrorEstimate PassSpread::estimateFrom(const Image& even, const Image& odd, int passes, double biasSquareSum,
                                       double biasNoiseSum, int biasHalf) {
  const size_t values = 3 * even.pixels.size();
  ErrorEstimate e;
  if (passes < 2) return e;
  e.source = ErrorSource::Passes;
  e.count = passes;
  e.noiseRmse = std::sqrt(
      meanOf(sumOver(even, [&](size_t i, int c) { return varianceOfMean(even, odd, passes, i, c); }), values));
  if (biasHalf > 0) {
    e.biasRmse = biasOf(biasSquareSum, biasNoiseSum, values);
    e.biasHalf = biasHalf;
  }
  return e;
}

ErrorEstimate PassSpread::estimate() const {
  return estimateFrom(even_, odd_, passes_, biasSquareSum_, biasNoiseSum_, biasHalf_);
}

Image PassSpread::standardError() const {
  Image out(even_.width, even_.height);
  if (passes_ < 2) return out;
  for (size_t i = 0; i < out.pixels.size(); ++i) {
    for (int c = 0; c < 3; ++c) out.pixels[i][c] = float(std::sqrt(varianceOfMean(even_, odd_, passes_, i, c)));
  }
  return out;
}

PassSpread::Moments PassSpread::moments() const {
  return {even_, odd_, snapshot_, snapshotPasses_, passes_, biasHalf_, biasSquareSum_, biasNoiseSum_, keep_, checkpoint_};
}

void PassSpread::restore(Moments m) {
  even_ = std::move(m.even);
  odd_ = std::move(m.odd);
  snapshot_ = std::move(m.snapshot);
  snapshotPasses_ = m.snapshotPasses;
  passes_ = m.passes;
  biasHalf_ = m.biasHalf;
  biasSquareSum_ = m.biasSquareSum;
  biasNoiseSum_ = m.biasNoiseSum;
  keep_ = m.keep;
  checkpoint_ = std::move(m.checkpoint);
}

ErrorEstimate sampleError(const Image& standardError, int spp) {
  ErrorEstimate e;
  if (spp < 2 || standardError.pixels.empty()) return e;
  e.source = ErrorSource::Samples;
  e.count = spp;
  e.noiseRmse = std::sqrt(meanOf(sumOver(standardError, [&](size_t i, int c) {
    const double se = standardError.pixels[i][c];
    return se * se;  // in double: a float square of 1e20 is inf
  }), 3 * standardError.pixels.size()));
  return e;
}

}  // namespace penumbra
