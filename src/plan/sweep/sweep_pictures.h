// The sweep's pictures beside its tables: runs.png, every run's image labelled with its
// settings, time and error, and tradeoff.png, the plotting script on results.csv.
#pragma once
#include "plan/sweep/sweep_results.h"
#include <string>
#include <vector>

namespace penumbra {

// Each returns "" when drawn, else one line saying why not (a machine without
// matplotlib still gets every result).
std::string drawRunsSheet(const std::string& dir, const std::vector<SweepRow>& rows, SweepMetric metric);
std::string drawTradeoff(const std::string& script, const std::string& dir, const std::vector<SweepRow>& rows,
                         const std::string& title, SweepMetric metric);

}  // namespace penumbra
