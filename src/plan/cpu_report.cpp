// The CPU fields, the cpu line and the contended note, one wording for render,
// sweep, batch and bench.
#include "plan/cpu_report.h"
#include "io/report_json.h"
#include "plan/media_report.h"
#include <fmt/format.h>
#include <nlohmann/json.hpp>

namespace penumbra {

void addCpuFields(nlohmann::json& j, const CpuTiming& t) {
  j["cpu_s"] = t.cpuSeconds;
  j["cpu_share"] = t.share;
  j["load_avg_1m"] = t.loadAverage >= 0.0 ? nlohmann::json(t.loadAverage) : nlohmann::json(nullptr);
}

std::string cpuLine(const CpuTiming& t) {
  const std::string load = t.loadAverage >= 0.0 ? fmt::format(", load {:.2f} at start", t.loadAverage) : "";
  return fmt::format("cpu {:.2f} s (user + sys), share {:.2f} of {} thread{}{}", t.cpuSeconds, t.share, t.threads,
                     t.threads == 1 ? "" : "s", load);
}

std::string contendedNote(const std::vector<CpuTiming>& spans, const std::string& what) {
  size_t contended = 0;
  const CpuTiming* lowest = nullptr;
  for (const CpuTiming& t : spans) {
    if (!t.contended()) continue;
    ++contended;
    if (!lowest || t.share < lowest->share) lowest = &t;
  }
  if (!lowest) return "";
  const std::string load = lowest->loadAverage >= 0.0 ? fmt::format(", load {:.2f} at start", lowest->loadAverage) : "";
  const std::string which =
      spans.size() == 1 ? fmt::format("the {}'s CPU share was {:.2f} of {} thread{}{}", what, lowest->share,
                                      lowest->threads, lowest->threads == 1 ? "" : "s", load)
                        : fmt::format("{} of {} {}s had a CPU share below {} (lowest {:.2f} of {} thread{}{})",
                                      contended, spans.size(), what, kContendedShare, lowest->share, lowest->threads,
                                      lowest->threads == 1 ? "" : "s", load);
  return fmt::format("times are contended: {}: other work kept the workers off their cores part of the time (or a "
                     "serial stage left them idle); compare cpu_s, or time again on a quiet machine",
                     which);
}

std::string statsReport(const RenderResult& result) {
  nlohmann::json stats = nlohmann::json::parse(statsToJson(result.stats));
  addCpuFields(stats, result.stats.cpu);
  stats["estimate"] = nlohmann::json::parse(estimateToJson(result.estimate));
  if (result.media) stats["media"] = mediaCountsJson(result.stats.rays);
  stats["notes"] = result.notes;
  return stats.dump(2) + "\n";
}

}  // namespace penumbra
