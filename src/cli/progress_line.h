// The one-line progress of a many-render command (sweep, batch): items done of
// total, the current item and its phase, elapsed time and an ETA from the pace so far.
#pragma once
#include <fmt/format.h>
#include <string>

namespace penumbra {

inline std::string clockTime(double s) {
  const int t = static_cast<int>(s + 0.5);
  return t >= 3600 ? fmt::format("{}:{:02}:{:02}", t / 3600, t / 60 % 60, t % 60)
                   : fmt::format("{}:{:02}", t / 60, t % 60);
}

// `paced` of the `remaining + paced` items still to do when the command started
// are finished; the ETA extrapolates their mean time to the rest.
inline std::string progressLine(const char* what, size_t done, size_t total, const std::string& item,
                                const std::string& phase, double elapsed, size_t paced, size_t remaining) {
  const std::string eta = remaining == 0 ? "done"
                          : paced == 0   ? "ETA --"
                                         : "ETA " + clockTime(elapsed / paced * remaining);
  return fmt::format("{} {}/{} | {} | {} | {} elapsed, {}", what, done, total, item, phase, clockTime(elapsed), eta);
}

}  // namespace penumbra
