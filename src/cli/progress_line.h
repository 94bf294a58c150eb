// Progress lines: a many-render command's (sweep, batch: items done of total, the
// current item and its phase) and one render's phase; elapsed time and an ETA in both.
#pragma once
#include <fmt/format.h>
#include <algorithm>
#include <string>

namespace penumbra {

inline std::string clockTime(double s) {
  const int t = static_cast<int>(s + 0.5);
  return t >= 3600 ? fmt::format("{}:{:02}:{:02}", t / 3600, t / 60 % 60, t % 60)
                   : fmt::format("{}:{:02}", t / 60, t % 60);
}

// `done` units of work took `elapsed` seconds and `remaining` are left: the ETA
// extrapolates the pace so far ("ETA --" before any is done, "done" after the last).
inline std::string etaText(double elapsed, double done, double remaining) {
  return remaining <= 0.0 ? "done" : done <= 0.0 ? "ETA --" : "ETA " + clockTime(elapsed / done * remaining);
}

// `paced` of the `remaining + paced` items (or their estimated seconds) still to do
// when the command started are finished; the ETA extrapolates their pace to the rest.
inline std::string progressLine(const char* what, size_t done, size_t total, const std::string& item,
                                const std::string& phase, double elapsed, double paced, double remaining) {
  return fmt::format("{} {}/{} | {} | {} | {} elapsed, {}", what, done, total, item, phase, clockTime(elapsed),
                     etaText(elapsed, double(paced), double(remaining)));
}

// One phase of one render (penumbra render): a bar, the percent done, elapsed time
// and ETA. `fraction` < 0: the phase has not counted its work yet (no bar, no ETA).
inline std::string phaseLine(const std::string& phase, double fraction, double elapsed) {
  constexpr int kWidth = 20;
  const bool known = fraction >= 0.0;
  const double f = known ? std::min(fraction, 1.0) : 0.0;
  const int filled = static_cast<int>(f * kWidth);
  const std::string percent = known ? fmt::format("{:3d}%", static_cast<int>(f * 100.0)) : std::string("  --");
  return fmt::format("{:<8} [{}{}] {} | {} elapsed, {}", phase, std::string(filled, '#'),
                     std::string(kWidth - filled, '.'), percent, clockTime(elapsed),
                     known ? etaText(elapsed, f, 1.0 - f) : std::string("ETA --"));
}

}  // namespace penumbra
