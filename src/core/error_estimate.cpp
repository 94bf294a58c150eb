// The noise RMSE of the mean image from its even and odd passes' means, and the
// photon-map bias from the gathers' smoothing probes, else the first-half/second-half
// check at 2, 4, 8, ... passes.
#include "core/error_estimate.h"
#include <fmt/format.h>
#include <algorithm>
#include <cmath>
#include <utility>

namespace penumbra {
namespace {

// Its mean over `values` pixel channels.
double meanOf(double sum, size_t values) { return values == 0 ? 0.0 : sum / double(values); }

// The variance of the mean of `passes` passes at one pixel channel, from the sums of
// the even and of the odd passes.
double varianceOfMean(const Image& even, const Image& odd, int passes, size_t i, int c) {
  const double ne = (passes + 1) / 2, no = passes / 2;
  const double d = double(even.pixels[i][c]) / ne - double(odd.pixels[i][c]) / no;
  return ne * no / (double(passes) * passes) * d * d;
}

bool lighting(const EmitterMask& mask, size_t i) { return mask.empty() || mask[i] == 0; }

void addInto(Image& sum, const Image& image) {
  if (sum.pixels.empty()) sum = image;
  else for (size_t i = 0; i < image.pixels.size(); ++i) sum.pixels[i] += image.pixels[i];
}

float signedRoot(double p) { return float(p < 0.0 ? -std::sqrt(-p) : std::sqrt(p)); }

// The image's and the lighting's noise figures from per-pixel-channel variances.
template <class F>
void setNoise(ErrorEstimate& e, const Image& like, const EmitterMask& mask, F variance) {
  double all = 0.0, lit = 0.0;
  size_t litPixels = 0;
  for (size_t i = 0; i < like.pixels.size(); ++i) {
    double v = 0.0;
    for (int c = 0; c < 3; ++c) v += variance(i, c);
    all += v;
    if (lighting(mask, i)) {
      lit += v;
      ++litPixels;
    }
  }
  e.noiseRmse = std::sqrt(meanOf(all, 3 * like.pixels.size()));
  // Every pixel sees an emitter: the lighting has no figure (not a zero one).
  e.lightingNoiseRmse = litPixels ? std::sqrt(meanOf(lit, 3 * litPixels)) : -1.0;
  e.emitterShare = like.pixels.empty() ? 0.0 : 1.0 - double(litPixels) / double(like.pixels.size());
}

// The drift product of one pixel channel (the square of its signed root).
double driftSquare(const Image& drift, size_t i, int c) {
  const double r = drift.pixels[i][c];
  return r * std::abs(r);
}

// The bias figures from the drift products at lighting pixels. A pixel's product has
// the spread of its noise, which at a caustic's edge under one camera sample is heavy
// tailed (a few pixels' products would outweigh every other's): so the bias counted is
// the sum over the coarse cells whose sum stands out of its own standard error
// (kBiasSignificance, from its blocks), as a mean over the lighting and over the image;
// elsewhere the passes agree within noise. The region is the box of the fewest such
// cells that hold kBiasRegionShare of it.
// With `noise` (a product of mean 0 and the same noise: SmoothingSums), a cell's
// variance is the sum of its blocks' noise sums squared, which a bias concentrated in
// a few blocks does not inflate (else it is the spread of the blocks' own sums), and
// the bound adds what the cells within noise may hold (kBiasBoundSigmas).
void setBias(ErrorEstimate& e, const Image& drift, const EmitterMask& mask, const Image* noise = nullptr) {
  const int w = drift.width, h = drift.height;
  struct Block {
    double sum = 0.0, noise = 0.0;
    bool used = false;
  };
  struct Sums {
    double sum = 0.0, squares = 0.0, reference = 0.0;
    size_t values = 0;
    void add(const Block& b) { sum += b.sum, squares += b.sum * b.sum, reference += b.noise * b.noise, ++values; }
    double variance(bool referenced) const {
      const double mean = values ? sum / double(values) : 0.0;
      return referenced ? reference : std::max(0.0, squares - mean * sum);
    }
    bool significant(bool referenced) const {
      return values > 1 && sum > kBiasSignificance * std::sqrt(variance(referenced));
    }
  };
  // Cell cx covers the pixels x with x * kBiasGrid / w == cx, from edge(cx, w) on.
  auto edge = [](int cell, int size) { return (cell * size + kBiasGrid - 1) / kBiasGrid; };
  // Each cell's blocks, `side` pixels a side from its own corner, in one array.
  const int side = std::max(1, std::min(w, h) / (kBiasGrid * kBiasBlocks));
  const int bw = (w / kBiasGrid + side) / side, bh = (h / kBiasGrid + side) / side;
  std::vector<Block> blocks(size_t(kBiasGrid) * bw * kBiasGrid * bh);
  size_t values = 0;
  for (int y = 0; y < h; ++y)
    for (int x = 0; x < w; ++x) {
      const size_t i = size_t(y) * w + x;
      if (!lighting(mask, i)) continue;
      values += 3;
      const int cx = x * kBiasGrid / w, cy = y * kBiasGrid / h;
      const int bx = cx * bw + (x - edge(cx, w)) / side, by = cy * bh + (y - edge(cy, h)) / side;
      Block& b = blocks[size_t(by) * (kBiasGrid * bw) + bx];
      for (int c = 0; c < 3; ++c) b.sum += driftSquare(drift, i, c);
      if (noise) for (int c = 0; c < 3; ++c) b.noise += driftSquare(*noise, i, c);
      b.used = true;
    }
  std::vector<Sums> cells(kBiasGrid * kBiasGrid);
  for (size_t b = 0; b < blocks.size(); ++b) {
    if (!blocks[b].used) continue;
    const int bx = int(b % (kBiasGrid * bw)), by = int(b / (kBiasGrid * bw));
    cells[size_t(by / bh) * kBiasGrid + bx / bw].add(blocks[b]);
  }
  const bool referenced = noise != nullptr;
  std::vector<int> order;
  double found = 0.0, hidden = 0.0, hiddenVariance = 0.0;
  for (size_t k = 0; k < cells.size(); ++k) {
    if (cells[k].significant(referenced)) order.push_back(int(k)), found += cells[k].sum;
    else hidden += cells[k].sum, hiddenVariance += cells[k].variance(referenced);
  }
  e.lightingBiasRmse = values ? std::sqrt(meanOf(found, values)) : -1.0;
  e.biasRmse = std::sqrt(meanOf(found, 3 * drift.pixels.size()));
  if (referenced && values) {
    const double bound = found + std::max(0.0, hidden + kBiasBoundSigmas * std::sqrt(hiddenVariance));
    e.lightingBiasBound = std::sqrt(meanOf(bound, values));
  }
  e.biasWithinNoise = order.empty();
  if (e.biasWithinNoise) return;
  std::stable_sort(order.begin(), order.end(), [&](int a, int b) { return cells[a].sum > cells[b].sum; });
  int cx0 = kBiasGrid, cx1 = 0, cy0 = kBiasGrid, cy1 = 0;
  double held = 0.0;
  for (int k : order) {
    if (held >= kBiasRegionShare * found) break;
    held += cells[k].sum;
    cx0 = std::min(cx0, k % kBiasGrid), cx1 = std::max(cx1, k % kBiasGrid + 1);
    cy0 = std::min(cy0, k / kBiasGrid), cy1 = std::max(cy1, k / kBiasGrid + 1);
  }
  e.biasRegion = {edge(cx0, w), edge(cx1, w), edge(cy0, h), edge(cy1, h)};
  double inside = 0.0;
  for (int k : order)
    if (k % kBiasGrid >= cx0 && k % kBiasGrid < cx1 && k / kBiasGrid >= cy0 && k / kBiasGrid < cy1) inside += cells[k].sum;
  e.biasRegionShare = inside / found;
  e.biasRegionArea = double(e.biasRegion.pixels()) / double(drift.pixels.size());
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
  if (e.lightingNoiseRmse >= 0.0 && e.emitterShare > 0.0) {
    out += fmt::format("; lighting (without the {:.1f}% of pixels that see an emitter) ~{:.3g}",
                       100.0 * e.emitterShare, e.lightingNoiseRmse);
  }
  if (e.biasRmse < 0.0) return out;
  // Where noise hides some of the probes' bias, how much it may be.
  const std::string bound = e.lightingBiasBound > e.lightingBiasRmse
                                ? fmt::format(", at most ~{:.3g} where noise hides it", e.lightingBiasBound)
                                : "";
  if (e.biasFromGathers && e.biasWithinNoise) {
    return out + "; photon-map bias: the gathers' smoothing is within noise" + bound;
  }
  const std::string halves = fmt::format("passes 1-{} to {}-{}", e.biasHalf, e.biasHalf + 1, 2 * e.biasHalf);
  if (e.biasWithinNoise) return out + fmt::format("; photon-map bias: {} agree within noise", halves);
  const std::string from = e.biasFromGathers ? "the gathers' smoothing, r against r/sqrt2" : "the drift from " + halves;
  out += fmt::format("; photon-map bias ~{:.3g} RMSE of the lighting ({}", e.lightingBiasRmse, from);
  const PixelBounds& r = e.biasRegion;
  if (!r.empty()) {
    out += fmt::format("; {:.0f}% of it in x {}-{}, y {}-{}, {:.0f}% of the image", 100.0 * e.biasRegionShare, r.x0,
                       r.x1 - 1, r.y0, r.y1 - 1, 100.0 * e.biasRegionArea);
  }
  out += ")" + bound;
  return out;
}

void PassSpread::add(const Image& image, int pass, const Image* smoothing) {
  addInto(pass % 2 == 0 ? even_ : odd_, image);
  // Probes count only when every pass brought one: a pass without one ends them.
  if (smoothing && smoothing_.filled() == std::min(pass, SmoothingSums::kGroups))
    addInto(smoothing_.groups[pass % SmoothingSums::kGroups], *smoothing);
  else smoothing_ = SmoothingSums();
  passes_ = pass + 1;
  if (passes_ != std::max(2, 2 * snapshotPasses_)) return;
  // Passes 1..h against h+1..2h, once each sequence has a pass in each half.
  if (snapshotPasses_ >= 2) {
    biasHalf_ = snapshotPasses_;
    drift_ = driftOf(snapshotEven_, snapshotOdd_, even_, odd_, biasHalf_);
    if (keep_) checkpoint_ = {snapshotEven_, snapshotOdd_, even_, odd_, passes_, biasHalf_};
  }
  snapshotEven_ = even_;
  snapshotOdd_ = odd_;
  snapshotPasses_ = passes_;
}

Image PassSpread::driftOf(const Image& firstEvenSum, const Image& firstOddSum, const Image& even, const Image& odd,
                          int half) {
  // Each of the four groups (even and odd passes, first and second half) has h/2 passes.
  const double n = half / 2;
  Image out(even.width, even.height);
  for (size_t i = 0; i < out.pixels.size(); ++i) {
    for (int ch = 0; ch < 3; ++ch) {
      const double firstEven = firstEvenSum.pixels[i][ch], firstOdd = firstOddSum.pixels[i][ch];
      const double evenDrift = (firstEven - (double(even.pixels[i][ch]) - firstEven)) / n;
      const double oddDrift = (firstOdd - (double(odd.pixels[i][ch]) - firstOdd)) / n;
      out.pixels[i][ch] = signedRoot(evenDrift * oddDrift);
    }
  }
  return out;
}

PassSpread::Products PassSpread::smoothingProducts(const SmoothingSums& smoothing, int passes) {
  // Group g holds the passes p < `passes` with p = g mod 4.
  double n[SmoothingSums::kGroups];
  for (int g = 0; g < SmoothingSums::kGroups; ++g) n[g] = (passes - g + SmoothingSums::kGroups - 1) / SmoothingSums::kGroups;
  const double ne = n[0] + n[2], no = n[1] + n[3];
  // A difference of two groups' means, scaled to the noise of the mean of both. Radii
  // shrink with passes, so groups 0 and 1 run slightly wider than 2 and 3: the
  // reference then holds a little of that drift too, which only makes it stricter.
  const double se = std::sqrt((1.0 / ne) / (1.0 / n[0] + 1.0 / n[2])), so = std::sqrt((1.0 / no) / (1.0 / n[1] + 1.0 / n[3]));
  const Image* g = smoothing.groups;
  Products out{Image(g[0].width, g[0].height), Image(g[0].width, g[0].height)};
  for (size_t i = 0; i < g[0].pixels.size(); ++i)
    for (int ch = 0; ch < 3; ++ch) {
      const double s0 = g[0].pixels[i][ch], s1 = g[1].pixels[i][ch], s2 = g[2].pixels[i][ch], s3 = g[3].pixels[i][ch];
      out.signal.pixels[i][ch] = signedRoot((s0 + s2) / ne * ((s1 + s3) / no));
      out.noise.pixels[i][ch] = signedRoot(se * (s0 / n[0] - s2 / n[2]) * (so * (s1 / n[1] - s3 / n[3])));
    }
  return out;
}

const Image* PassSpread::biasProducts(Products& storage) const {
  if (smoothing_.complete()) {
    storage = smoothingProducts(smoothing_, passes_);
    return &storage.signal;
  }
  return biasHalf_ > 0 ? &drift_ : nullptr;
}

ErrorEstimate PassSpread::fromHalves(const Image& even, const Image& odd, int passes, const PassCheckpoint& cp,
                                     const SmoothingSums& smoothing, const EmitterMask& mask) {
  const Image drift = cp.half > 0 ? driftOf(cp.firstEven, cp.firstOdd, cp.even, cp.odd, cp.half) : Image();
  return estimateFrom(even, odd, passes, drift, cp.half, smoothing, mask);
}

ErrorEstimate PassSpread::estimateFrom(const Image& even, const Image& odd, int passes, const Image& drift,
                                       int biasHalf, const SmoothingSums& smoothing, const EmitterMask& mask) {
  ErrorEstimate e;
  if (passes < 2) return e;
  e.source = ErrorSource::Passes;
  e.count = passes;
  setNoise(e, even, mask, [&](size_t i, int c) { return varianceOfMean(even, odd, passes, i, c); });
  if (smoothing.complete()) {
    const Products p = smoothingProducts(smoothing, passes);
    setBias(e, p.signal, mask, &p.noise);
    e.biasFromGathers = true;
  } else if (biasHalf > 0) {
    setBias(e, drift, mask);
    e.biasHalf = biasHalf;
  }
  return e;
}

ErrorEstimate PassSpread::estimate() const {
  return estimateFrom(even_, odd_, passes_, drift_, biasHalf_, smoothing_, mask_);
}

Image PassSpread::standardError() const {
  Image out(even_.width, even_.height);
  if (passes_ < 2) return out;
  for (size_t i = 0; i < out.pixels.size(); ++i) {
    for (int c = 0; c < 3; ++c) out.pixels[i][c] = float(std::sqrt(varianceOfMean(even_, odd_, passes_, i, c)));
  }
  return out;
}

Image PassSpread::bias() const {
  const int w = even_.width, h = even_.height;
  Image out(w, h);
  Products storage;
  const Image* products = biasProducts(storage);
  if (!products) return out;
  // One pixel's product has the spread of its noise: the view shows the mean of the
  // lighting pixels' products around it, as the root of its positive part.
  for (int y = 0; y < h; ++y)
    for (int x = 0; x < w; ++x) {
      if (!lighting(mask_, size_t(y) * w + x)) continue;
      glm::dvec3 sum(0.0);
      int n = 0;
      for (int yy = std::max(0, y - kBiasViewRadius); yy <= std::min(h - 1, y + kBiasViewRadius); ++yy)
        for (int xx = std::max(0, x - kBiasViewRadius); xx <= std::min(w - 1, x + kBiasViewRadius); ++xx) {
          const size_t j = size_t(yy) * w + xx;
          if (!lighting(mask_, j)) continue;
          for (int c = 0; c < 3; ++c) sum[c] += driftSquare(*products, j, c);
          ++n;
        }
      out.pixels[size_t(y) * w + x] = Color(glm::sqrt(glm::max(sum / double(n), glm::dvec3(0.0))));
    }
  return out;
}

PassSpread::Moments PassSpread::moments() const {
  return {even_, odd_, snapshotEven_, snapshotOdd_, drift_, snapshotPasses_, passes_, biasHalf_, keep_, checkpoint_,
          smoothing_};
}

void PassSpread::restore(Moments m) {
  even_ = std::move(m.even);
  odd_ = std::move(m.odd);
  snapshotEven_ = std::move(m.snapshotEven);
  snapshotOdd_ = std::move(m.snapshotOdd);
  drift_ = std::move(m.drift);
  snapshotPasses_ = m.snapshotPasses;
  passes_ = m.passes;
  biasHalf_ = m.biasHalf;
  keep_ = m.keep;
  checkpoint_ = std::move(m.checkpoint);
  smoothing_ = std::move(m.smoothing);
}

ErrorEstimate sampleError(const Image& standardError, int spp, const EmitterMask& mask) {
  ErrorEstimate e;
  if (spp < 2 || standardError.pixels.empty()) return e;
  e.source = ErrorSource::Samples;
  e.count = spp;
  setNoise(e, standardError, mask, [&](size_t i, int c) {
    const double se = standardError.pixels[i][c];
    return se * se;  // in double: a float square of 1e20 is inf
  });
  return e;
}

}  // namespace penumbra
