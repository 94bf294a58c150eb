// Runs the project's plotting script (scripts/plot_tradeoff.py) on a sweep's
// results.csv without a shell, with Debian's python3, where matplotlib lives.
#pragma once
#include <string>

namespace penumbra {

// Draws `png` from `csv` with `metric` (sweep_results.h's names) on the error axis and
// `cost` ("wall" or "cpu") on the time axis; returns "" on success, else one line saying why not.
std::string drawTradeoffPlot(const std::string& script, const std::string& csv, const std::string& png,
                             const std::string& title, const std::string& metric, const std::string& cost = "wall");

}  // namespace penumbra
