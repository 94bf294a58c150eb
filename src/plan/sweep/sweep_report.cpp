// report.md of a sweep: the knobs, the reference and its noise, what was reused, the
// estimate against what was spent, the best run, the Pareto front, the time to reach
// each error, the gate's trade-off and every run.
#include "plan/sweep/sweep_report.h"
#include "plan/cpu_report.h"
#include <cmath>
#include <fmt/format.h>
#include <algorithm>
#include <iterator>

namespace penumbra {
namespace {

std::string knobList(const SweepSpec& spec) {
  std::string s;
  for (const SweepKnob& k : spec.knobs) {
    std::string keys, values;
    for (const std::string& key : k.keys) keys += (keys.empty() ? "" : ", ") + key;
    for (const std::string& v : k.values) values += (values.empty() ? "" : ",") + v;
    s += fmt::format("- `{}` ({}): {}\n", k.name, keys, values);
  }
  return s;
}

std::string settings(const SweepSpec& spec, const SweepRow& r) {
  std::string s;
  for (size_t k = 0; k < spec.knobs.size(); ++k) s += fmt::format(" {} |", r.values[k]);
  return s;
}

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
  md += t.errorOf == ErrorFigure::Image
            ? std::string(" Errors are over the whole image (`--error-of image`).")
            : fmt::format(" Errors are over the lighting's pixels (`--error-of lighting`): those that see an emitter "
                          "directly ({:.1f}% of the image at most) are left out, their aliased edges being the "
                          "camera's error.", 100.0 * t.emitterShare);
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
