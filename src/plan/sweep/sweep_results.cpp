// results.csv rows both ways, the Pareto front, and the markdown report.
#include "plan/sweep/sweep_results.h"
#include "core/error.h"
#include "core/cpu_time.h"
#include <cmath>
#include <fmt/format.h>
#include <fmt/ranges.h>
#include <algorithm>
#include <iterator>
#include <fstream>
#include <sstream>
#include <string_view>
#include <type_traits>
#include <variant>

namespace penumbra {
namespace {

// Every column after the run id and the knobs, once: its name and the row's field,
// which csvLine writes and parseRow reads; times are "_s" columns in seconds.
using Field = std::variant<bool SweepRow::*, double SweepRow::*, uint64_t SweepRow::*, std::string SweepRow::*>;
struct Column {
  const char* name;
  Field field;
};
const Column kColumns[] = {
    {"reference", &SweepRow::reference}, {"load_s", &SweepRow::load}, {"bvh_s", &SweepRow::bvh},
    {"emit_s", &SweepRow::emit}, {"maps_s", &SweepRow::maps}, {"precompute_s", &SweepRow::precompute},
    {"render_s", &SweepRow::render}, {"render_median_s", &SweepRow::renderMedian}, {"total_s", &SweepRow::total},
    {"total_cpu_s", &SweepRow::totalCpu}, {"spent_s", &SweepRow::spent},
    {"cpu_s", &SweepRow::cpu}, {"cpu_share", &SweepRow::cpuShare}, {"load_avg_1m", &SweepRow::loadAverage},
    {"camera_rays", &SweepRow::cameraRays}, {"shadow_rays", &SweepRow::shadowRays},
    {"reflection_rays", &SweepRow::reflectionRays}, {"refraction_rays", &SweepRow::refractionRays},
    {"gate_queries", &SweepRow::gateQueries}, {"shadow_rays_avoided", &SweepRow::shadowRaysAvoided},
    {"gather_queries", &SweepRow::gatherQueries}, {"photons_emitted", &SweepRow::photonsEmitted},
    {"photons_stored", &SweepRow::photonsStored}, {"rmse", &SweepRow::rmse}, {"rel_mse", &SweepRow::relMse},
    {"psnr", &SweepRow::psnr}, {"worst1pct_rmse", &SweepRow::worstRmse},
    {"noise_rmse", &SweepRow::noiseRmse}, {"gate", &SweepRow::gate},
    {"ungated_render_s", &SweepRow::ungatedRender}, {"ungated_shadow_rays", &SweepRow::ungatedShadowRays},
    {"gate_rmse", &SweepRow::gateRmse}, {"reused", &SweepRow::reused}, {"image", &SweepRow::image}};

std::vector<std::string> splitCsv(const std::string& line) {
  std::vector<std::string> out;
  std::stringstream in(line);
  std::string cell;
  while (std::getline(in, cell, ',')) out.push_back(cell);
  if (!line.empty() && line.back() == ',') out.emplace_back();
  return out;
}

std::string joinCsv(const std::vector<std::string>& cells) {
  std::string line;
  for (size_t i = 0; i < cells.size(); ++i) line += (i ? "," : "") + cells[i];
  return line;
}

std::string cellOf(const SweepRow& r, const Column& c) {
  const std::string_view name(c.name);
  const bool seconds = name.size() > 2 && name.substr(name.size() - 2) == "_s";
  return std::visit(
      [&](auto field) -> std::string {
        const auto& v = r.*field;
        using T = std::decay_t<decltype(v)>;
        if constexpr (std::is_same_v<T, bool>) return v ? "1" : "0";
        else if constexpr (std::is_same_v<T, double>) return fmt::format(seconds ? "{:.4f}" : "{:.6g}", v);
        else if constexpr (std::is_same_v<T, uint64_t>) return std::to_string(v);
        else return v;
      },
      c.field);
}

void readCell(SweepRow& r, const Column& c, const std::string& cell) {
  std::visit(
      [&](auto field) {
        auto& v = r.*field;
        using T = std::decay_t<decltype(v)>;
        if constexpr (std::is_same_v<T, bool>) v = cell == "1";
        else if constexpr (std::is_same_v<T, double>) v = std::stod(cell);
        else if constexpr (std::is_same_v<T, uint64_t>) v = std::stoull(cell);
        else v = cell;
      },
      c.field);
}

SweepRow parseRow(const std::vector<std::string>& cells, size_t knobs) {
  SweepRow r;
  r.id = cells[0];
  r.values.assign(cells.begin() + 1, cells.begin() + 1 + long(knobs));
  for (size_t i = 0; i < std::size(kColumns); ++i) readCell(r, kColumns[i], cells[1 + knobs + i]);
  return r;
}

}  // namespace

void fillCounts(SweepRow& row, const RenderStats& st) {
  row.cameraRays = st.rays.camera;
  row.shadowRays = st.rays.shadow;
  row.reflectionRays = st.rays.reflection;
  row.refractionRays = st.rays.refraction;
  row.gateQueries = st.rays.gateQueries;
  row.shadowRaysAvoided = st.rays.shadowRaysAvoided;
  row.gatherQueries = st.rays.gatherQueries;
  row.photonsEmitted = st.emitted.total();
  row.photonsStored = st.stored.total();
}

std::vector<std::string> csvHeader(const std::vector<SweepKnob>& knobs) {
  std::vector<std::string> h = {"run"};
  for (const SweepKnob& k : knobs) h.push_back(k.name);
  for (const Column& c : kColumns) h.push_back(c.name);
  return h;
}

std::string csvLine(const SweepRow& r) {
  std::vector<std::string> c = {r.id};
  c.insert(c.end(), r.values.begin(), r.values.end());
  for (const Column& col : kColumns) c.push_back(cellOf(r, col));
  return joinCsv(c);
}

std::string resultsCsv(const std::vector<SweepKnob>& knobs, const std::vector<SweepRow>& rows) {
  std::string text = joinCsv(csvHeader(knobs)) + "\n";
  for (const SweepRow& r : rows) {
    if (!r.id.empty()) text += csvLine(r) + "\n";
  }
  return text;
}

std::map<std::string, SweepRow> readFinishedRows(const std::string& path, const std::vector<SweepKnob>& knobs) {
  std::map<std::string, SweepRow> rows;
  std::ifstream in(path);
  if (!in) return rows;
  std::string line;
  const std::string header = joinCsv(csvHeader(knobs));
  if (!std::getline(in, line)) return rows;
  if (line != header) {
    // A header alone holds no finished run: a failed sweep's, which a retry replaces.
    std::string row;
    while (std::getline(in, row)) {
      if (!row.empty()) break;
    }
    if (row.empty()) return rows;
    // The same run and knob columns: the file is another penumbra version's (its columns differ).
    const std::vector<std::string> theirs = splitCsv(line), ours = csvHeader(knobs);
    const size_t named = 1 + knobs.size();
    const bool sameKnobs = theirs.size() >= named && std::equal(ours.begin(), ours.begin() + long(named), theirs.begin());
    throw InputError(path + (sameKnobs ? ": written by another version of penumbra (its columns differ)"
                                       : ": written by a sweep with other knobs (header differs)") +
                     "; use another -o folder or --force to start again");
  }
  const size_t columns = csvHeader(knobs).size();
  while (std::getline(in, line)) {
    const std::vector<std::string> cells = splitCsv(line);
    if (cells.size() != columns) continue;  // never written by us: skip, the run is redone
    try {
      SweepRow r = parseRow(cells, knobs.size());
      rows[r.id] = r;
    } catch (const std::exception&) {
      continue;
    }
  }
  return rows;
}

const char* metricName(SweepMetric metric) { return kMetricNames[static_cast<size_t>(metric)]; }

SweepMetric parseMetric(const std::string& name) {
  std::string known;
  for (size_t i = 0; i < std::size(kMetricNames); ++i) {
    if (name == kMetricNames[i]) return static_cast<SweepMetric>(i);
    known += (i ? ", " : "") + std::string(kMetricNames[i]);
  }
  throw InputError("--metric: unknown metric '" + name + "' (known: " + known + ")");
}

double metricError(const SweepRow& r, SweepMetric metric) {
  switch (metric) {
    case SweepMetric::RelMse: return r.relMse;
    case SweepMetric::Rmse: return r.rmse;
    case SweepMetric::Psnr:
    case SweepMetric::RmseClamped: return std::pow(10.0, -r.psnr / 20.0);
  }
  return r.rmse;
}

size_t bestRun(const std::vector<SweepRow>& rows, SweepMetric metric) {
  size_t best = rows.size();
  for (size_t i = 0; i < rows.size(); ++i) {
    if (rows[i].reference) continue;
    if (best == rows.size() || metricError(rows[i], metric) < metricError(rows[best], metric)) best = i;
  }
  return best;
}

double runCost(const SweepRow& r, SweepCost cost) { return cost == SweepCost::Cpu ? r.totalCpu : r.total; }

bool contendedRows(const std::vector<SweepRow>& rows) {
  for (const SweepRow& r : rows) {
    CpuTiming t;
    t.wallSeconds = r.spent;
    t.share = r.cpuShare;
    if (!r.id.empty() && t.contended()) return true;
  }
  return false;
}

std::vector<size_t> paretoFront(const std::vector<SweepRow>& rows, SweepMetric metric, SweepCost cost) {
  std::vector<size_t> front;
  for (size_t i = 0; i < rows.size(); ++i) {
    if (rows[i].reference) continue;
    bool beaten = false;
    const double tb = runCost(rows[i], cost), eb = metricError(rows[i], metric);
    for (size_t j = 0; j < rows.size() && !beaten; ++j) {
      if (j == i || rows[j].reference) continue;
      const double ta = runCost(rows[j], cost), ea = metricError(rows[j], metric);
      beaten = ta <= tb && ea <= eb && (ta < tb || ea < eb);
    }
    if (!beaten) front.push_back(i);
  }
  std::sort(front.begin(), front.end(), [&](size_t a, size_t b) { return runCost(rows[a], cost) < runCost(rows[b], cost); });
  return front;
}

void fillErrors(SweepRow& row, const ImageError& error, const ErrorEstimate& own, ErrorFigure figure) {
  row.rmse = error.rmse;
  row.relMse = error.relMse;
  row.psnr = error.psnr;
  row.worstRmse = error.worstRmse;
  row.noiseRmse = sweepNoiseRmse(own, figure);
}

void setRenderTimes(SweepRow& row, std::vector<double> renders) {
  std::sort(renders.begin(), renders.end());
  const size_t n = renders.size();
  row.render = renders.front();
  row.renderMedian = n % 2 ? renders[n / 2] : 0.5 * (renders[n / 2 - 1] + renders[n / 2]);
}

std::string reusedList(bool bvh, uint64_t prefixOf, bool maps) {
  std::vector<std::string> parts;
  if (bvh) parts.push_back("bvh");
  if (prefixOf > 0) parts.push_back(fmt::format("photons(prefix of {})", prefixOf));
  if (maps) parts.push_back("maps");
  return fmt::format("{}", fmt::join(parts, ";"));
}

double sweepNoiseRmse(const ErrorEstimate& e, ErrorFigure figure) {
  if (figure == ErrorFigure::Lighting && e.lightingKnown()) return e.lightingNoiseRmse;
  return e.known() ? e.noiseRmse : -1.0;
}

bool withinReferenceNoise(const SweepRow& r, double referenceNoiseRmse) {
  return !r.reference && referenceNoiseRmse > 0.0 && r.rmse <= kWithinReferenceNoise * referenceNoiseRmse;
}

}  // namespace penumbra
