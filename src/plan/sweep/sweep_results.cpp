// results.csv rows both ways, the Pareto front, and the markdown report.
#include "plan/sweep/sweep_results.h"
#include "core/error.h"
#include "plan/cpu_report.h"
#include <cmath>
#include <fmt/format.h>
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

std::string knobList(const SweepSpec& spec) {
  std::string s;
  for (const SweepKnob& k : spec.knobs) {
    std::string keys;
    for (const std::string& key : k.keys) keys += (keys.empty() ? "" : ", ") + key;
    s += fmt::format("- `{}` ({}): {}\n", k.name, keys, joinCsv(k.values));
  }
  return s;
}

std::string settings(const SweepSpec& spec, const SweepRow& r) {
  std::string s;
  for (size_t k = 0; k < spec.knobs.size(); ++k) s += fmt::format(" {} |", r.values[k]);
  return s;
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

double sweepNoiseRmse(const ErrorEstimate& e) { return e.known() ? e.noiseRmse : -1.0; }

bool withinReferenceNoise(const SweepRow& r, double referenceNoiseRmse) {
  return !r.reference && referenceNoiseRmse > 0.0 && r.rmse <= kWithinReferenceNoise * referenceNoiseRmse;
}

namespace {

// The fastest run reaching each error of a 1-2-5 ladder between the runs' best and
// worst error under `metric`: what a given accuracy costs on this scene.
std::string timeToReach(const SweepSpec& spec, const std::vector<SweepRow>& rows, SweepMetric metric, SweepCost cost) {
  double lo = 0.0, hi = 0.0;
  for (const SweepRow& r : rows) {
    const double e = metricError(r, metric);
    if (r.reference || !(e > 0.0) || !std::isfinite(e)) continue;
    lo = lo > 0.0 ? std::min(lo, e) : e;
    hi = std::max(hi, e);
  }
  if (!(lo > 0.0)) return "";
  const bool cpu = cost == SweepCost::Cpu;
  std::string md = fmt::format("\n## Time to reach an error\n\nThe {} run whose {} is at most E:\n\n| E | {} |",
                               cpu ? "cheapest (in CPU seconds)" : "fastest", metricName(metric), cpu ? "CPU s" : "time s");
  std::string rule = "|---|---|";
  for (const SweepKnob& k : spec.knobs) { md += " " + k.name + " |"; rule += "---|"; }
  md += "\n" + rule + "\n";
  const double steps[] = {1.0, 2.0, 5.0};
  for (double decade = std::pow(10.0, std::floor(std::log10(lo))); decade <= hi * 10.0; decade *= 10.0) {
    for (double step : steps) {
      const double target = decade * step;
      if (target < lo || target > 2.0 * hi) continue;
      size_t fastest = rows.size();
      for (size_t i = 0; i < rows.size(); ++i) {
        if (rows[i].reference || metricError(rows[i], metric) > target) continue;
        if (fastest == rows.size() || runCost(rows[i], cost) < runCost(rows[fastest], cost)) fastest = i;
      }
      if (fastest < rows.size()) {
        md += fmt::format("| {:.3g} | {:.3f} |", target, runCost(rows[fastest], cost)) + settings(spec, rows[fastest]) + "\n";
      }
    }
  }
  return md;
}

}  // namespace

std::string reportMarkdown(const std::string& scene, const SweepSpec& spec, const std::vector<SweepRow>& grid,
                           const SweepTotals& t, SweepMetric metric) {
  // Only finished rows (a --threads list's earlier sessions leave the others empty).
  std::vector<SweepRow> rows;
  std::copy_if(grid.begin(), grid.end(), std::back_inserter(rows), [](const SweepRow& r) { return !r.id.empty(); });
  std::string md = fmt::format("# Sweep of {}\n\n{} runs. Knobs (`--set` keys they write):\n\n{}\n", scene,
                               rows.size(), knobList(spec));
  md += fmt::format("**Reference:** {}", t.referenceNote);
  double referenceNoise = t.referenceNoiseRmse;
  for (const SweepRow& r : rows) {
    if (!r.reference) continue;
    referenceNoise = r.noiseRmse;
    md += r.noiseRmse >= 0.0 ? fmt::format(". Its own error estimate, how far it is from converged: ~{:.3g} RMSE of "
                                           "noise (docs/accuracy.md)", r.noiseRmse)
                             : ". It has no error estimate of its own (one pass of one sample)";
  }
  md += "\n\n";
  size_t alike = 0;
  for (const SweepRow& r : rows) alike += withinReferenceNoise(r, referenceNoise);
  if (referenceNoise > 0.0) {
    md += fmt::format("**Within the reference's noise:** a run whose RMSE is at most {:.3g} ({:.3g} x the reference's "
                      "own ~{:.3g}) is marked `~ref` ({} of {} runs): its own error is no larger than the reference's, "
                      "so the differences among such runs are the reference's noise, not theirs. A longer reference "
                      "(`--reference-passes`) tells them apart.\n\n",
                      kWithinReferenceNoise * referenceNoise, kWithinReferenceNoise, referenceNoise, alike, rows.size());
  }
  md += "**Error:** RMSE, relative MSE (mean of (a-r)^2/(r^2+0.01)) and PSNR (on values clamped to [0,1]) "
        "from OpenImageIO's ImageBufAlgo against the reference; `worst 1%` is the RMSE over the 1% of pixels "
        "with the largest squared error in that run.\n\n"
        "**Time** (`time s`, `total_s`) is what a run costs as a standalone render: every stage it needs, shared or "
        "not, every progressive pass's photons and maps included (a prefix's emission counted as its share of the "
        "largest emission's time); `CPU s` (`total_cpu_s`) is the same account in CPU seconds.\n\n";
  if (t.repeat > 1) {
    md += fmt::format("**Repeats:** each run's frame was rendered {} times on its maps; `render_s` (and the total) "
                      "is the fastest, `render_median_s` the median.\n\n", t.repeat);
  }
  const double denom = t.photonSeconds + t.renderSeconds;
  md += fmt::format(
      "## What was reused\n\n- Embree scenes built: {}\n- photon emissions: {} (smaller budgets cut out of "
      "them as prefixes: {})\n- photon map builds: {}\n- runs resumed from an earlier results.csv: {}\n\n"
      "Sweep wall time {:.2f} s; its distinct photon passes {:.2f} s plus its render passes {:.2f} s = "
      "{:.2f} s; ratio {:.2f}.\n\n",
      t.bvhBuilds, t.emissions, t.prefixCuts, t.mapBuilds, t.resumed, t.wallSeconds, t.photonSeconds,
      t.renderSeconds, denom, denom > 0 ? t.wallSeconds / denom : 0.0);
  if (t.cpu.known()) md += "Sweep " + cpuLine(t.cpu) + "; each run's in `results.csv` (`cpu_s`, `cpu_share`).\n\n";
  if (t.estimatedSeconds > 0.0 && t.cpu.known()) {
    const std::string busy = t.estimatedBusySeconds > 1.5 * t.estimatedSeconds
                                 ? fmt::format(", ~{:.0f} s at the machine's load when it started", t.estimatedBusySeconds)
                                 : "";
    md += fmt::format("Estimated before the first photon: ~{:.0f} s on {} threads{}; spent {:.0f} s of wall time, "
                      "{:.0f} CPU-s ({:.0f} s of {} busy threads).\n\n",
                      t.estimatedSeconds, t.cpu.threads, busy, t.wallSeconds, t.cpu.cpuSeconds,
                      t.cpu.cpuSeconds / std::max(t.cpu.threads, 1), t.cpu.threads);
  }

  std::string head = "|";
  std::string rule = "|";
  for (const SweepKnob& k : spec.knobs) { head += " " + k.name + " |"; rule += "---|"; }
  head += " time s | CPU s | RMSE | relMSE | PSNR | worst 1% | |\n";
  rule += "---|---|---|---|---|---|---|\n";
  auto line = [&](const SweepRow& r) {
    const char* mark = r.reference ? "reference" : withinReferenceNoise(r, referenceNoise) ? "~ref" : "";
    return "|" + settings(spec, r) +
           fmt::format(" {:.3f} | {:.3f} | {:.4g} | {:.4g} | {:.2f} | {:.4g} | {} |\n", r.total, r.totalCpu, r.rmse,
                       r.relMse, r.psnr, r.worstRmse, mark);
  };
  // On a contended machine wall seconds follow the other work; CPU seconds follow the run's.
  const SweepCost cost = contendedRows(rows) ? SweepCost::Cpu : SweepCost::Wall;
  const char* costName = cost == SweepCost::Cpu ? "CPU seconds" : "time";
  md += fmt::format("**Ranked by** {} (`--metric`); cost is {}.", metricName(metric),
                    cost == SweepCost::Cpu ? "CPU seconds (`total_cpu_s`), because some runs did not have their cores "
                                             "all the time (`cpu_share` below 0.9), so their wall time is partly "
                                             "other work's"
                                           : "wall time (`total_s`)");
  md += "\n\n";
  if (const size_t best = bestRun(rows, metric); best < rows.size()) {
    md += "## Best run\n\n" + head + rule + line(rows[best]) + "\n";
    if (withinReferenceNoise(rows[best], referenceNoise)) {
      md += "Its error is within the reference's own noise (`~ref`): it is not measurably better than the other "
            "runs so marked.\n\n";
    }
  }
  const std::vector<size_t> front = paretoFront(rows, metric, cost);
  md += fmt::format("## Pareto front\n\nRuns that no other run beats on both {} and {}, cheapest first:\n\n", costName,
                    metricName(metric)) + head + rule;
  size_t frontAlike = 0;
  for (size_t i : front) {
    md += line(rows[i]);
    frontAlike += withinReferenceNoise(rows[i], referenceNoise);
  }
  if (frontAlike > 1) {
    md += fmt::format("\n{} runs of the front are within the reference's noise (`~ref`): against this reference only "
                      "the cheapest of them is known to be worth its cost.\n", frontAlike);
  }

  md += timeToReach(spec, rows, metric, cost);

  bool anyGate = false;
  for (const SweepRow& r : rows) anyGate = anyGate || r.gate;
  if (anyGate) {
    md += "\n## The gate's trade-off\n\nEach gated run rendered again with every shadow ray cast (the same "
          "maps): the shadow rays the gate avoided, and the error it adds against that ungated image.\n\n|";
    for (const SweepKnob& k : spec.knobs) md += " " + k.name + " |";
    md += " shadow rays | avoided | ungated shadow rays | render s | ungated render s | RMSE gated vs ungated |\n|";
    for (size_t k = 0; k < spec.knobs.size(); ++k) md += "---|";
    md += "---|---|---|---|---|---|\n";
    for (const SweepRow& r : rows) {
      if (!r.gate) continue;
      md += "|" + settings(spec, r) +
            fmt::format(" {} | {} | {} | {:.3f} | {:.3f} | {:.4g} |\n", r.shadowRays, r.shadowRaysAvoided,
                        r.ungatedShadowRays, r.render, r.ungatedRender, r.gateRmse);
    }
  }
  md += "\n## Every run\n\n" + head + rule;
  for (const SweepRow& r : rows) md += line(r);
  md += "\nPer-stage times, ray and photon counts: `results.csv`. Plot: `tradeoff.png`.\n";
  return md;
}

}  // namespace penumbra
