// The sweep's runs.png and tradeoff.png (plan/sweep/sweep_pictures.h).
#include "plan/sweep/sweep_pictures.h"
#include "plan/sweep/plot_script.h"
#include "io/contact_sheet.h"
#include <fmt/format.h>
#include <filesystem>

namespace penumbra {

namespace fs = std::filesystem;

std::string drawRunsSheet(const std::string& dir, const std::vector<SweepRow>& rows, SweepMetric metric) {
  std::vector<SheetTile> tiles;
  for (const SweepRow& r : rows) {
    if (r.image.empty()) continue;
    tiles.push_back({(fs::path(dir) / r.image).string(),
                     {r.id, r.reference ? fmt::format("{:.2f} s  the reference", r.total)
                                        : fmt::format("{:.2f} s  {} {:.3g}", r.total, metricName(metric),
                                                      metricError(r, metric))}});
  }
  return writeContactSheet((fs::path(dir) / "runs.png").string(), tiles);
}

std::string drawTradeoff(const std::string& script, const std::string& dir, const std::vector<SweepRow>& rows,
                         const std::string& title, SweepMetric metric) {
  return drawTradeoffPlot(script, (fs::path(dir) / "results.csv").string(), (fs::path(dir) / "tradeoff.png").string(),
                          title, metricName(metric), contendedRows(rows) ? "cpu" : "wall");
}

}  // namespace penumbra
