// How far a render is from converged without a reference: the spread of its
// independent estimates (progressive passes, else a pixel's samples) as the standard
// error of the mean image, and the photon-map bias that passes shrink, kept apart.
#pragma once
#include "core/image.h"
#include "core/pixel_bounds.h"
#include <cmath>
#include <cstdint>
#include <string>
#include <utility>
#include <vector>

namespace penumbra {

// Where an image's noise figure comes from: the spread of progressive passes or of a
// pixel's samples, or for one pass of one sample (the pixel centres) probes beside it
// (trace/probe_error.h).
enum class ErrorSource { None, Passes, Samples, Probes };

struct ErrorEstimate {
  ErrorSource source = ErrorSource::None;
  int count = 0;  // passes, or samples per pixel, the spread is taken over; pixels probed
  // Standard error of the image: sqrt(mean over pixels and channels of SE^2), the
  // RMSE the image has against its own converged mean. < 0: unknown.
  double noiseRmse = -1.0;
  // Passes only: the photon-map bias, the drift of each pixel's expected value between
  // passes 1..h and h+1..2h (the last power of two 2h), measured per pixel with its own
  // noise taken out, at pixels that do not see an emitter, summed over the coarse cells
  // where it stands out of their noise (elsewhere it counts 0), as an RMSE over the
  // whole image. < 0: not measured (fewer than 4 passes).
  double biasRmse = -1.0;
  int biasHalf = 0;
  // The bias was measured from the gathers' own smoothing probes (SmoothingSums), not
  // the drift between halves: then biasHalf is 0.
  bool biasFromGathers = false;
  // The lighting: the same figures over the pixels that do not see an emitter directly
  // or through mirrors and glass (whose edges alias under the camera's samples and
  // carry no photon-map light). The figures a target error aims at by default.
  double lightingNoiseRmse = -1.0;
  double lightingBiasRmse = -1.0;
  // From the gathers' probes: the lighting's bias figure plus what the cells within
  // noise may hold, at kBiasBoundSigmas of their noise: an upper bound. < 0: none.
  double lightingBiasBound = -1.0;
  double emitterShare = 0.0;  // the share of the image's pixels that see an emitter
  // Where the bias sits: the box of the coarse cells (kBiasGrid) that hold most of it
  // (kBiasRegionShare), and its share inside that box. Empty: no bias beyond its own noise.
  PixelBounds biasRegion;
  double biasRegionShare = 0.0;
  double biasRegionArea = 0.0;  // the box's share of the image's pixels
  // No cell's bias stands out of its noise (kBiasSignificance): the passes agree
  // within noise (and the bias figures are 0).
  bool biasWithinNoise = false;
  // Samples or probes of one pass read photon maps they all share, whose noise the
  // figure then leaves out (and says so).
  bool sharedMaps = false;
  // Probes only: none of them found an error, so the figure (0) is a lower bound:
  // pixels they did not reach may hold some. Shown as "at least", never "~".
  bool lowerBound = false;

  bool known() const { return noiseRmse >= 0.0; }
  bool lightingKnown() const { return lightingNoiseRmse >= 0.0; }
  // Noise and bias together, sqrt(noise^2 + bias^2) (bias 0 when not measured); < 0 unknown.
  double totalRmse() const { return combined(noiseRmse, biasRmse); }
  double lightingTotalRmse() const { return combined(lightingNoiseRmse, lightingBiasRmse); }

 private:
  static double combined(double noise, double bias) {
    return noise < 0.0 ? -1.0 : bias > 0.0 ? std::sqrt(noise * noise + bias * bias) : noise;
  }
};

// "~0.012 RMSE (noise, from 8 passes)", or why there is no figure.
std::string describeError(const ErrorEstimate& e);

// The fewest passes the bias check reads: two halves, each with an even and an odd pass;
// for the probes, a pass in each of their four groups.
constexpr int kBiasMinPasses = 4;
// The coarse grid (cells per side) the bias region is named in.
constexpr int kBiasGrid = 8;
// A cell's sum of drift products stands out of noise beyond this many of its standard
// errors, estimated from the spread of its blocks' sums: a pixel's three channels, and
// neighbours that share photons, are not independent draws; blocks nearly are. A cell
// holds about kBiasBlocks x kBiasBlocks blocks, enough for its spread to be known.
constexpr double kBiasSignificance = 3.5;
constexpr int kBiasBlocks = 8;
// The bias bound counts the cells within noise at their sum plus this many of their
// standard errors.
constexpr double kBiasBoundSigmas = 2.0;
// The bias region holds this share of the sum of the cells whose bias stands out of
// their noise (the box of the fewest such cells that do).
constexpr double kBiasRegionShare = 0.9;
// The bias view's pixel shows the mean drift product over (2r+1)^2 pixels around it.
constexpr int kBiasViewRadius = 2;

// Per pixel, 1 where it sees an emitter directly or through mirrors and glass
// (trace/emitter_mask.h); empty: none known, every pixel is lighting.
using EmitterMask = std::vector<uint8_t>;

// The photon gathers' smoothing probes (trace/render.h: RenderOptions::smoothing), each
// pass's per-pixel estimate of its own photon-map bias, summed by pass modulo 4. The
// even passes' mean times the odd passes' has the squared bias as its mean with each
// pixel's noise taken out; the same product of the differences (passes 0 - 2 mod 4
// times 1 - 3) has mean 0 and the same noise, photon sharing and heavy tails: the
// reference a block's product is judged against. Empty: the model does not probe them.
struct SmoothingSums {
  static constexpr int kGroups = 4;
  Image groups[kGroups];
  // The groups that hold a pass (every one from pass 4 on).
  int filled() const {
    int n = 0;
    while (n < kGroups && !groups[n].pixels.empty()) ++n;
    return n;
  }
  // Every group holds a pass: the bias figure can be formed.
  bool complete() const { return filled() == kGroups; }
};

// The bias check's inputs at its last power of two, 2h passes: the sums of the even and
// of the odd passes among the first h, and among all 2h. A tile keeps them so the merge
// computes the whole frame's check to the bit.
struct PassCheckpoint {
  Image firstEven, firstOdd, even, odd;
  int passes = 0, half = 0;  // 2h and h; half 0: no check yet
};

// Even and odd passes take their camera samples from two independently scrambled
// sequences, each stratified in itself, so their means are independent estimates of
// the pixel: with n_e and n_o passes, the mean's variance is n_e n_o / P^2 times
// their difference squared. A spread over the passes would also count the strata's
// differences, which the mean of a stratified sequence does not have.
//
// The bias check at 2h passes (h >= 2): the even passes' drift from the first h to the
// next h, times the odd passes' drift. The two sequences are independent, so the
// product's mean is the drift squared with each pixel's noise taken out, and neither
// factor mixes strata of one sequence with another's (at a sharp edge the halves of one
// sequence differ far more than independent draws would).
//
// Where the passes carry the gathers' smoothing probes, the bias figure is theirs: it
// sees a bias that shrinks slowly with passes, which a drift between halves cannot
// tell from its noise until passes are many; the drift check stays for models that do
// not probe.
class PassSpread {
 public:
  // `image`: pass `pass` (0-based, in order); `smoothing`: its smoothing probe, given
  // with every pass or with none.
  void add(const Image& image, int pass, const Image* smoothing = nullptr);
  // The pixels that see an emitter: left out of the lighting figures and the bias.
  void setEmitterMask(EmitterMask mask) { mask_ = std::move(mask); }

  int passes() const { return passes_; }
  // The estimate after the passes added so far (noise needs 2 passes, bias 4).
  ErrorEstimate estimate() const;
  // Per pixel, the standard error of the mean of the passes (0 with one pass).
  Image standardError() const;
  // Per pixel, the bias check's drift: the root of the mean drift product over the
  // lighting pixels within kBiasViewRadius (0 where noise outweighs it, at emitter
  // pixels and before 4 passes): the "bias" view.
  Image bias() const;

  // Everything add() has accumulated: a frame's saved passes carry it to another
  // process, which restore()s it and continues at the next pass.
  struct Moments {
    Image even, odd, snapshotEven, snapshotOdd, drift;
    int snapshotPasses = 0, passes = 0, biasHalf = 0;
    bool keep = false;  // a tile's: the checkpoint too
    PassCheckpoint checkpoint;
    SmoothingSums smoothing;
  };
  Moments moments() const;
  void restore(Moments m);
  // What a tile of the frame keeps for the merge, per pixel so the merged figure is
  // the whole frame's to the bit: the sums of the even and odd passes, and (after
  // keepCheckpoint) the bias check's inputs.
  const Image& evenSum() const { return even_; }
  const Image& oddSum() const { return odd_; }
  void keepCheckpoint() { keep_ = true; }
  const PassCheckpoint& checkpoint() const { return checkpoint_; }
  const SmoothingSums& smoothingSums() const { return smoothing_; }
  // The estimate of `passes` passes whose even and odd sums are these, with the bias
  // check of `checkpoint` or of `smoothing` where given, over the pixels `mask` leaves
  // to the lighting.
  static ErrorEstimate fromHalves(const Image& even, const Image& odd, int passes, const PassCheckpoint& checkpoint,
                                  const SmoothingSums& smoothing, const EmitterMask& mask);

 private:
  static ErrorEstimate estimateFrom(const Image& even, const Image& odd, int passes, const Image& drift, int biasHalf,
                                    const SmoothingSums& smoothing, const EmitterMask& mask);
  // Per pixel channel, the signed roots of the products of the even and the odd passes'
  // mean smoothing probes, and of their noise reference (SmoothingSums).
  struct Products {
    Image signal, noise;
  };
  static Products smoothingProducts(const SmoothingSums& smoothing, int passes);
  // The products the bias figure reads (the probes' where kept, else the drift), and
  // whether there are any yet.
  const Image* biasProducts(Products& storage) const;
  // Per pixel channel, the signed root of the drift product (float holds roots of
  // squares that would overflow it).
  static Image driftOf(const Image& firstEven, const Image& firstOdd, const Image& even, const Image& odd, int half);

  Image even_, odd_;  // the sums of the even and of the odd passes
  Image snapshotEven_, snapshotOdd_;  // ... among the first `snapshotPasses_`
  int snapshotPasses_ = 0;
  int passes_ = 0;
  Image drift_;  // the last check's driftOf
  int biasHalf_ = 0;
  bool keep_ = false;
  PassCheckpoint checkpoint_;
  SmoothingSums smoothing_;
  EmitterMask mask_;
};

// An estimate from one pass's per-pixel standard error of the mean (from its samples:
// its even and odd samples' means, as passes' above), squared and averaged in double;
// the lighting's over the pixels `mask` leaves to it.
ErrorEstimate sampleError(const Image& standardError, int spp, const EmitterMask& mask = {});

}  // namespace penumbra
