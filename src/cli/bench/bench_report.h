// What penumbra bench prints and writes: min and median per stage and thread
// count, the speed-up of each thread count over the fewest, the CPU share, and the
// compute-only control beside them; the same as JSON with every sample.
#pragma once
#include "cli/bench/bench_run.h"
#include <string>
#include <vector>

namespace penumbra {

struct MinMedian {
  double min = 0.0, median = 0.0;
};
// The smallest and the median of `values` (the mean of the middle two for an even count).
MinMedian minMedian(std::vector<double> values);

// One table per scene, each ending with the control's row and a line comparing the
// scene's total speed-up with the control's.
std::string benchTable(const BenchOutcome& outcome);

std::string benchJson(const BenchOutcome& outcome);

}  // namespace penumbra
