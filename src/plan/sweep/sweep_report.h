// report.md of a sweep (plan/sweep/sweep_report.cpp).
#pragma once
#include "plan/sweep/sweep_results.h"
#include <string>
#include <vector>

namespace penumbra {

std::string reportMarkdown(const std::string& scene, const SweepSpec& spec,
                           const std::vector<SweepRow>& rows, const SweepTotals& totals,
                           SweepMetric metric = SweepMetric::RelMse);

}  // namespace penumbra
