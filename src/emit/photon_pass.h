// The skeleton every photon pass shares (the classic shadow and indirect passes,
// the physical global and caustic passes): per-light counts into fixed-size
// batches, each batch traced by one task into its thread's blocks, the prefix cuts
// recorded as it goes, the photons returned in batch order. Only the per-batch
// set-up and the per-photon trace differ between passes.
#pragma once
#include "core/photon_batches.h"
#include "emit/batch_buffers.h"
#include "emit/budget.h"
#include "emit/emit.h"
#include "emit/photon_prefix.h"
#include <tbb/parallel_for.h>
#include <vector>

namespace penumbra {

// `startBatch(batch)` runs on the task that traces the batch and returns the
// photon tracer for it, `trace(out)` once per photon (its random stream keyed by
// the batch, so the photons do not depend on the thread count). `weights` and
// `counts` are the light split the prefix cuts rescale; `cuts` (if any) receives
// them for options.prefixBudgets. `emitted` receives the photons traced.
template <class Photon, class StartBatch>
PhotonBatches<Photon> runPhotonPass(const std::vector<double>& weights, const std::vector<uint64_t>& counts,
                                    const EmitOptions& options, PrefixCuts* cuts, uint64_t& emitted,
                                    StartBatch&& startBatch) {
  const std::vector<PhotonBatch> batches = makeBatches(counts, options.batchSize);
  BatchBuffers<Photon> buffers(batches.size());
  PrefixCuts* prefix = nullptr;
  if (cuts && !options.prefixBudgets.empty()) {
    *cuts = PrefixCuts(weights, counts, options.prefixBudgets, batches);
    prefix = cuts;
  }
  tbb::parallel_for(size_t(0), batches.size(), [&](size_t b) {
    const PhotonBatch& batch = batches[b];
    auto trace = startBatch(batch);
    buffers.fill(b, [&](BatchAppender<Photon>& out) {
      traceBatch(prefix, b, batch.count, out, [&](uint64_t) { trace(out); });
    });
    progressAdd(options.progress, batch.count);
  });
  if (prefix) prefix->finish(buffers.sizes());
  emitted = 0;
  for (uint64_t c : counts) emitted += c;
  return buffers.finish();
}

}  // namespace penumbra
