// penumbra sweep's results: one row per run, results.csv (rewritten atomically
// after every run, read back to resume), the Pareto front and the rules the report
// ranks and marks runs by (report.md itself: sweep_report.h).
#pragma once
#include "plan/sweep/sweep_spec.h"
#include "plan/render_budget.h"
#include "core/stats.h"
#include "io/image_compare.h"
#include <map>
#include <string>
#include <vector>

namespace penumbra {

// One finished run. Times are what the run costs as a standalone render (shared
// stages counted in full, a prefix's emission by its share of the photons);
// `spentSeconds` is what the sweep actually spent on it.
struct SweepRow {
  std::string id;
  std::vector<std::string> values;  // one per knob
  bool reference = false;           // the default reference itself (error 0)
  double load = 0, bvh = 0, emit = 0, maps = 0, precompute = 0, render = 0, total = 0, spent = 0;
  double totalCpu = 0;  // `total` in CPU seconds: what the same lone render's stages take of the cores
  // --repeat N: render is the fastest of the run's N frames, this their median.
  double renderMedian = 0;
  // The process's CPU time over `spent`, its share of (spent x threads), the load at the run's start.
  double cpu = 0, cpuShare = 0, loadAverage = -1;
  uint64_t cameraRays = 0, shadowRays = 0, reflectionRays = 0, refractionRays = 0;
  uint64_t gateQueries = 0, shadowRaysAvoided = 0, gatherQueries = 0;
  uint64_t photonsEmitted = 0, photonsStored = 0;
  double rmse = 0, relMse = 0, psnr = 0, worstRmse = 0;
  double noiseRmse = -1;  // the run's own error estimate without the reference; < 0 unknown
  bool gate = false;
  double ungatedRender = 0, gateRmse = 0;  // gated runs: the same run with every shadow ray cast
  uint64_t ungatedShadowRays = 0;
  std::string reused;  // what came from earlier runs: "bvh", "photons(prefix of N)", "maps"
  std::string image;   // relative to the sweep folder
};

// Rays and photons of a finished render, into its row.
void fillCounts(SweepRow& row, const RenderStats& stats);
// The run's error columns: its image against the reference (over the pixels --error-of
// keeps), and its own noise estimate over the same pixels.
void fillErrors(SweepRow& row, const ImageError& error, const ErrorEstimate& own, ErrorFigure figure);
// --repeat: the render times of the run's frames; the fastest is render_s, the median
// render_median_s.
void setRenderTimes(SweepRow& row, std::vector<double> renders);
// The reused column: "bvh;photons(prefix of N);maps", what came from earlier runs.
std::string reusedList(bool bvh, uint64_t prefixOf, bool maps);

// The CSV header for these knobs.
std::vector<std::string> csvHeader(const std::vector<SweepKnob>& knobs);
std::string csvLine(const SweepRow& row);
// The whole results.csv: the header and every finished row (rows with an id).
std::string resultsCsv(const std::vector<SweepKnob>& knobs, const std::vector<SweepRow>& rows);

// Rows of an earlier results.csv with the same header, by run id; an absent file
// gives none. Throws InputError when the file exists but has another header.
std::map<std::string, SweepRow> readFinishedRows(const std::string& path,
                                                    const std::vector<SweepKnob>& knobs);

// What the front, the plot and the best run rank by (every metric stays in
// results.csv). relMSE by default: plain RMSE lets a few bright caustic pixels
// outweigh visible noise everywhere else. rmse-clamped is the RMSE of values clamped
// to [0, 1], the one PSNR reports, so the two rank alike.
enum class SweepMetric { RelMse, Rmse, Psnr, RmseClamped };
inline constexpr const char* kMetricNames[] = {"relmse", "rmse", "psnr", "rmse-clamped"};
const char* metricName(SweepMetric metric);
SweepMetric parseMetric(const std::string& name);  // throws InputError naming the choices
// The row's error under `metric`, lower better (PSNR as its clamped RMSE).
double metricError(const SweepRow& row, SweepMetric metric);

// What the front and the time to reach an error rank a run's cost by: total_s, or
// total_cpu_s when the runs' times were contended (below).
enum class SweepCost { Wall, Cpu };
double runCost(const SweepRow& row, SweepCost cost);
// Whether some run (of those long enough to judge) had its cores less than
// kContendedShare of the time (core/cpu_time.h): then its wall seconds follow the
// machine's other work, and the sweep ranks by CPU seconds.
bool contendedRows(const std::vector<SweepRow>& rows);

// Rows no other row beats on both cost and the metric (the reference excluded),
// cheapest first.
std::vector<size_t> paretoFront(const std::vector<SweepRow>& rows, SweepMetric metric = SweepMetric::RelMse,
                                SweepCost cost = SweepCost::Wall);

// The noise figure the sweep reads from a render's own estimate (a run's noise_rmse,
// the reference's own error), over the pixels its errors are of (--error-of): the
// lighting's (pixels that see no emitter) or the whole image's; < 0 unknown.
double sweepNoiseRmse(const ErrorEstimate& e, ErrorFigure figure);

// A run whose RMSE against the reference is at most this times the reference's own
// noise: measured RMSE^2 is about the run's own error^2 plus the reference's, so the
// run's own error is no larger than the reference's and differences among such runs
// are the reference's, not theirs.
constexpr double kWithinReferenceNoise = 1.4142135623730951;  // sqrt(2)
bool withinReferenceNoise(const SweepRow& row, double referenceNoiseRmse);

// The run with the lowest error under `metric` (the reference excluded), rows.size()
// when there is none.
size_t bestRun(const std::vector<SweepRow>& rows, SweepMetric metric);

struct SweepTotals {
  double wallSeconds = 0;       // the whole sweep
  CpuTiming cpu;                // ... and its CPU time
  double photonSeconds = 0;     // sum over distinct photon settings: emission (share) + map build
  double renderSeconds = 0;     // sum of every render pass (precompute + render, ungated ones too)
  size_t emissions = 0, prefixCuts = 0, mapBuilds = 0, bvhBuilds = 0, resumed = 0;
  std::string referenceNote;    // which reference the errors are against
  double referenceNoiseRmse = -1;  // the sweep's own long reference's noise estimate; < 0 unknown
  ErrorFigure errorOf = ErrorFigure::Lighting;  // the pixels the errors are over (--error-of)
  double emitterShare = 0;  // lighting: the largest share of a run's pixels left out as seeing an emitter
  double estimatedSeconds = 0;  // what the sweep announced before its first photon (sweep_estimate.h)
  double estimatedBusySeconds = 0;  // ... stretched by the machine's load at the start
  int repeat = 1;               // frames rendered per run (--repeat)

  // Adds another session's counts and stage seconds (a --threads list's sessions).
  void addCounts(const SweepTotals& o) {
    estimatedSeconds += o.estimatedSeconds;
    estimatedBusySeconds += o.estimatedBusySeconds;
    photonSeconds += o.photonSeconds;
    renderSeconds += o.renderSeconds;
    emissions += o.emissions;
    prefixCuts += o.prefixCuts;
    mapBuilds += o.mapBuilds;
    bvhBuilds += o.bvhBuilds;
    resumed += o.resumed;
  }
};


}  // namespace penumbra
