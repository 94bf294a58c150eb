// penumbra sweep's sessions: one for the whole grid, or with a threads knob one per
// thread count, so every stage of a run is timed at its own count.
#include "cli/sweep_run.h"
#include "core/cpu_time.h"

namespace penumbra {

SweepOutcome runSweep(const SweepRequest& request) {
  const std::vector<int> counts = threadCounts(request.spec);
  if (counts.empty()) return runSweepSession(request, request.threads, false);
  // The most threads first, so the highest run (the default reference's) comes
  // first; later sessions resume the rows the earlier wrote.
  SweepRequest each = request;
  SweepOutcome out;
  size_t counters[5] = {0, 0, 0, 0, 0};
  double seconds[2] = {0.0, 0.0};
  const CpuSpan clock;
  for (size_t i = 0; i < counts.size(); ++i) {
    if (i > 0) each.force = false;
    out = runSweepSession(each, counts[i], true);
    SweepTotals& t = out.totals;
    const size_t* mine[5] = {&t.resumed, &t.emissions, &t.prefixCuts, &t.mapBuilds, &t.bvhBuilds};
    for (int c = 0; c < 5; ++c) counters[c] += *mine[c];
    seconds[0] += t.renderSeconds;
    seconds[1] += t.photonSeconds;
  }
  // The outcome's rows are the last session's (every row); its totals, all sessions'.
  SweepTotals& t = out.totals;
  size_t* all[5] = {&t.resumed, &t.emissions, &t.prefixCuts, &t.mapBuilds, &t.bvhBuilds};
  for (int c = 0; c < 5; ++c) *all[c] = counters[c];
  t.renderSeconds = seconds[0];
  t.photonSeconds = seconds[1];
  t.cpu = clock.timing(counts.front());
  t.wallSeconds = t.cpu.wallSeconds;
  return out;
}

}  // namespace penumbra
