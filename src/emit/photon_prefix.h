// Smaller photon budgets inside one larger emission. Every light's photons come
// from (light, batch) streams, so its first n photons do not depend on its budget:
// a run with fewer photons takes each light's first n_l photons' stored hits from
// the largest emission, power rescaled, instead of emitting again (penumbra sweep).
#pragma once
#include "core/photon.h"
#include "core/photon_batches.h"
#include "emit/budget.h"
#include <cstddef>
#include <cstdint>
#include <vector>

namespace penumbra {

// The photons a smaller budget would have stored, as one range per light of the
// full emission's stored sequence (which is light-major: batches in light order).
struct PrefixCut {
  uint64_t budget = 0;            // the smaller total
  std::vector<uint64_t> emitted;  // per light: its share of `budget`
  std::vector<size_t> begin, end; // per light: its stored photons in the full array
  std::vector<float> powerScale;  // per light: full share / this share (count_l / emitted_l)
};

// Filled during one emission: where each requested budget's photons end. Batches
// record into their own slots, so the recording shares nothing between threads.
class PrefixCuts {
 public:
  PrefixCuts() = default;
  // `counts` = the full emission's photons per light (splitByWeight(weights, total));
  // a budget whose split asks some light for more than the full one is skipped
  // (it is not a prefix: emit it fresh).
  PrefixCuts(const std::vector<double>& weights, const std::vector<uint64_t>& counts,
             const std::vector<uint64_t>& budgets, const std::vector<PhotonBatch>& batches);

  // In-batch photon counts after which batch b must record its stored size, ascending.
  struct Mark {
    uint64_t after;  // photons of the batch traced
    size_t cut;      // index into cuts()
  };
  const std::vector<Mark>& marks(size_t batch) const { return marks_[batch]; }
  void record(size_t batch, size_t mark, size_t storedInBatch) { recorded_[batch][mark] = storedInBatch; }

  // After the emission: each batch's stored photon count, in batch order.
  void finish(const std::vector<size_t>& storedPerBatch);

  const std::vector<PrefixCut>& cuts() const { return cuts_; }
  const PrefixCut* find(uint64_t budget) const;

 private:
  std::vector<PrefixCut> cuts_;
  std::vector<PhotonBatch> batches_;
  std::vector<std::vector<Mark>> marks_;
  std::vector<std::vector<size_t>> recorded_;
};

// Copies a cut's photons out of the full emission. Shadow photons carry no power.
PhotonArray<ShadowPhoton> takePrefix(const PhotonBatches<ShadowPhoton>& all, const PrefixCut& cut);
// Indirect photons carry power / count: each light's are rescaled to the smaller
// count (then packed again, so within the packing's 2^-8 of a fresh emission's).
PhotonArray<IndirectPhoton> takePrefix(const PhotonBatches<IndirectPhoton>& all, const PrefixCut& cut);
PhotonArray<VolumePhoton> takePrefix(const PhotonBatches<VolumePhoton>& all, const PrefixCut& cut);  // as indirect

// Traces batch b's photons one at a time through `tracePhoton(i)`, recording the
// cuts' marks as it goes. Keeps the loop of each emitter free of the bookkeeping.
template <class Out, class Trace>
void traceBatch(PrefixCuts* cuts, size_t b, uint64_t count, const Out& out, Trace&& tracePhoton) {
  const std::vector<PrefixCuts::Mark>* marks = cuts ? &cuts->marks(b) : nullptr;
  size_t next = 0;
  for (uint64_t i = 0; i < count; ++i) {
    tracePhoton(i);
    while (marks && next < marks->size() && (*marks)[next].after == i + 1) {
      cuts->record(b, next, out.size());
      ++next;
    }
  }
}

}  // namespace penumbra
