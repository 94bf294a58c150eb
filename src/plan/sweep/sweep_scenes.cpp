// Folders of a several-scene sweep and its summary, scenes.md.
#include "plan/sweep/sweep_scenes.h"
#include "core/error.h"
#include <fmt/format.h>
#include <algorithm>
#include <filesystem>
#include <map>

namespace penumbra {

namespace fs = std::filesystem;

std::vector<std::string> sceneFolders(const std::vector<std::string>& scenes, const std::string& out) {
  if (scenes.size() == 1) return {out};
  std::vector<std::string> folders;
  std::map<std::string, std::string> byFolder;
  for (const std::string& scene : scenes) {
    const std::string folder = (fs::path(out) / fs::path(scene).stem()).string();
    const auto [at, fresh] = byFolder.emplace(folder, scene);
    if (!fresh) {
      throw InputError("sweep: " + at->second + " and " + scene + " would share the folder " + folder +
                       "; sweep them separately");
    }
    folders.push_back(folder);
  }
  return folders;
}

std::string scenesMarkdown(const std::vector<SceneSweep>& sweeps, SweepMetric metric) {
  std::string md = fmt::format(
      "# Sweep of {} scenes\n\nBest: the lowest {} against the scene's own reference; fastest: the lowest total "
      "time, in CPU seconds where the scene's runs were contended (its report.md says so). Each scene's report.md "
      "has its Pareto front, time-to-error table and every run.\n\n"
      "| scene | runs | best run | its total s | its {} | fastest run | its total s | its {} | report |\n"
      "|---|---:|---|---:|---:|---|---:|---:|---|\n",
      sweeps.size(), metricName(metric), metricName(metric), metricName(metric));
  for (const SceneSweep& s : sweeps) {
    const std::vector<SweepRow>& rows = s.outcome.rows;
    const size_t best = bestRun(rows, metric);
    const SweepCost cost = contendedRows(rows) ? SweepCost::Cpu : SweepCost::Wall;
    size_t fastest = rows.size();
    for (size_t i = 0; i < rows.size(); ++i) {
      if (rows[i].reference) continue;
      if (fastest == rows.size() || runCost(rows[i], cost) < runCost(rows[fastest], cost)) fastest = i;
    }
    auto cells = [&](size_t i) {
      // PSNR as itself (higher is better), the others as their error.
      const double e = metric == SweepMetric::Psnr ? rows[i].psnr : metricError(rows[i], metric);
      return i < rows.size() ? fmt::format("{} | {:.3f} | {:.4g}", rows[i].id, rows[i].total, e)
                             : std::string("- | - | -");
    };
    const std::string report = (fs::path(s.folder).filename() / "report.md").string();
    md += fmt::format("| {} | {} | {} | {} | [{}]({}) |\n", s.scene, rows.size(), cells(best), cells(fastest), report,
                      report);
  }
  return md;
}

}  // namespace penumbra
