// penumbra sweep's sessions: one for the whole grid, or with a threads knob one per
// thread count, so every stage of a run is timed at its own count.
#include "plan/sweep/sweep_run.h"
#include "core/cpu_time.h"

namespace penumbra {

SweepOutcome runSweep(const SweepRequest& request) {
  const std::vector<int> counts = threadCounts(request.spec);
  if (counts.empty()) return runSweepSession(request, request.session.threads, false);
  // The most threads first, so the highest run (the default reference's) comes
  // first; later sessions resume the rows the earlier wrote.
  SweepRequest each = request;
  SweepOutcome out;
  SweepTotals sum;
  const CpuSpan clock;
  for (size_t i = 0; i < counts.size(); ++i) {
    if (i > 0) each.force = false;
    out = runSweepSession(each, counts[i], true);
    sum.addCounts(out.totals);
  }
  // The outcome's rows are the last session's (every row); its totals, all sessions'.
  sum.referenceNote = out.totals.referenceNote;
  sum.referenceNoiseRmse = out.totals.referenceNoiseRmse;
  sum.errorOf = out.totals.errorOf;
  sum.emitterShare = out.totals.emitterShare;
  sum.repeat = out.totals.repeat;
  sum.cpu = clock.timing(counts.front());
  sum.wallSeconds = sum.cpu.wallSeconds;
  out.totals = sum;
  return out;
}

}  // namespace penumbra
