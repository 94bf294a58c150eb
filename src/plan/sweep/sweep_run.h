// penumbra sweep: renders every run of a grid with one loaded geometry, one
// Embree scene and one photon emission per group of runs that can share them,
// measures each run's stages and error, and writes results.csv, report.md, the
// runs' images and tradeoff.png into one folder; a rerun resumes.
#pragma once
#include "plan/sweep/sweep_results.h"
#include "plan/sweep/sweep_spec.h"
#include "plan/session_options.h"
#include <functional>
#include <string>
#include <vector>

namespace penumbra {

// Where a sweep is: `done` of `total` runs after `seconds`, the current `run` in
// `phase`; `paced` runs finished by this session and `remaining` still to render
// (what an ETA extrapolates from).
struct SweepProgress {
  size_t done = 0, total = 0;
  std::string run;
  std::string phase;
  double seconds = 0.0;
  size_t paced = 0, remaining = 0;
  // The same in estimated seconds (plan/sweep/sweep_estimate.h), the reference's
  // included: runs differ in cost, so the ETA extrapolates these when they are known.
  double pacedSeconds = 0.0, remainingSeconds = 0.0;
};

struct SweepRequest {
  // Every run's: threads (one count; a list is the threads knob), memory, the plan,
  // -D (before each run's knobs), the budget, the phases inside each render.
  SessionOptions session;
  std::string scenePath;
  std::string outDir;
  SweepSpec spec;
  std::string referencePath;  // an EXR; empty: the sweep renders its own (below)
  // Without referencePath: the run at every knob's highest value with this many times
  // its progressive passes (a longer render by the same consistent estimator); 1 =
  // that run itself, marked as the reference row.
  int referencePasses = 8;
  std::string aov;            // empty: the scene's
  bool force = false;         // redo every run, even those results.csv has
  bool compareGate = true;    // gated runs: render again ungated for the gate's trade-off
  std::string plotScript;     // scripts/plot_tradeoff.py; empty: no plot
  SweepMetric metric = SweepMetric::RelMse;  // what the front, plot and best run rank by
  // --error-of: the pixels every error column is over; lighting leaves out those that
  // see an emitter directly (their aliased edges are the camera's error).
  ErrorFigure errorOf = ErrorFigure::Lighting;
  // Told on the sweep's own thread as each run's phase changes.
  std::function<void(const SweepProgress&)> progress;
  // Told once, before the first photon: what the sweep is estimated to cost.
  std::function<void(const std::string&)> notice;
  int repeat = 1;                    // --repeat: frames per run, the fastest and the median kept
  bool planOnly = false;             // load and plan every run (InputError on a bad one), render nothing
};

struct SweepOutcome {
  std::vector<SweepRow> rows;  // in grid order
  SweepTotals totals;
  std::vector<std::string> notes;  // the scene's load notes; e.g. the plot could not be drawn
};

// Every run is loaded and checked (InputError, naming the run) before the first renders.
// A threads knob (--threads 1,2) runs one session per count (plan/sweep/sweep_sessions.cpp).
SweepOutcome runSweep(const SweepRequest& request);
// One session of `threads` workers; with `onlyThatCount`, just the runs of that value
// of the threads knob (the others' rows are read back from results.csv).
SweepOutcome runSweepSession(const SweepRequest& request, int threads, bool onlyThatCount);

}  // namespace penumbra
