// How far a render is from converged without a reference: the spread of its
// independent estimates (progressive passes, else a pixel's samples) as the standard
// error of the mean image, and the photon-map bias that passes shrink, kept apart.
#pragma once
#include "core/image.h"
#include <string>

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
  // Passes only: the change, beyond noise, between the mean of the first `biasHalf`
  // passes and of the next `biasHalf`: photon-map bias that the shrinking radii take
  // away. A lower bound on what is left of it. < 0: not measured (fewer than 2 passes).
  double biasRmse = -1.0;
  int biasHalf = 0;
  // Samples or probes of one pass read photon maps they all share, whose noise the
  // figure then leaves out (and says so).
  bool sharedMaps = false;
  // Probes only: none of them found an error, so the figure (0) is a lower bound:
  // pixels they did not reach may hold some. Shown as "at least", never "~".
  bool lowerBound = false;

  bool known() const { return noiseRmse >= 0.0; }
};

// "~0.012 RMSE (noise, from 8 passes)", or why there is no figure.
std::string describeError(const ErrorEstimate& e);

// The noise of progressive passes' mean, and the bias check at each power of two.
// The bias check's inputs at its last power of two, 2h passes: the sum of the first h
// (`first`), the sum before the last pass, the last pass, and the even and odd sums
// after it. A tile keeps them so the merge computes the whole frame's check to the bit.
struct PassCheckpoint {
  Image first, before, pass, even, odd;
  int passes = 0, half = 0;  // 2h and h; half 0: no check yet
};

// Even and odd passes take their camera samples from two independently scrambled
// sequences, each stratified in itself, so their means are independent estimates of
// the pixel: with n_e and n_o passes, the mean's variance is n_e n_o / P^2 times
// their difference squared. A spread over the passes would also count the strata's
// differences, which the mean of a stratified sequence does not have.
class PassSpread {
 public:
  // `sumBefore`: the sum of passes 0..pass-1 (unused at pass 0); `image`: pass `pass`.
  // Call before adding `image` into the sum.
  void add(const Image& sumBefore, const Image& image, int pass);

  int passes() const { return passes_; }
  // The estimate after the passes added so far (noise needs 2 passes).
  ErrorEstimate estimate() const;
  // Per pixel, the standard error of the mean of the passes (0 with one pass).
  Image standardError() const;

  // Everything add() has accumulated: a frame's saved passes carry it to another
  // process, which restore()s it and continues at the next pass.
  struct Moments {
    Image even, odd, snapshot;
    int snapshotPasses = 0, passes = 0, biasHalf = 0;
    double biasSquareSum = 0.0, biasNoiseSum = 0.0;
    bool keep = false;  // a tile's: the checkpoint too
    PassCheckpoint checkpoint;
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
  // The estimate of `passes` passes whose even and odd sums are these, with the bias
  // check of `checkpoint`.
  static ErrorEstimate fromHalves(const Image& even, const Image& odd, int passes, const PassCheckpoint& checkpoint);

 private:
  static ErrorEstimate estimateFrom(const Image& even, const Image& odd, int passes, double biasSquareSum,
                                    double biasNoiseSum, int biasHalf);
  // The bias check's sums over pixels and channels (squared difference of the halves,
  // and the variance of the mean then).
  static void biasSums(const Image& first, const Image& before, const Image& pass, const Image& even,
                       const Image& odd, int passes, int half, double& squares, double& noise);

  Image even_, odd_;  // the sums of the even and of the odd passes
  Image snapshot_;  // the sum of the first `snapshotPasses_` passes
  int snapshotPasses_ = 0;
  int passes_ = 0;
  double biasSquareSum_ = 0.0, biasNoiseSum_ = 0.0;
  int biasHalf_ = 0;
  bool keep_ = false;
  PassCheckpoint checkpoint_;
};

// An estimate from one pass's per-pixel standard error of the mean (from its samples:
// its even and odd samples' means, as passes' above), squared and averaged in double.
ErrorEstimate sampleError(const Image& standardError, int spp);

}  // namespace penumbra
