// penumbra bench: the user's own scenes rendered at each thread count several
// times through the render session, the thread counts interleaved (1, 2, 1, 2, ...)
// so drift on a shared machine hits each alike, beside the compute-only control
// (cli/bench/compute_control.h) measured between them in the same run.
#pragma once
#include "plan/cpu_report.h"
#include "plan/pipeline.h"
#include "plan/session_options.h"
#include <cstdint>
#include <functional>
#include <string>
#include <vector>

namespace penumbra {

struct BenchRequest {
  // Every render's: memory, the plan, loading, -D, the phases inside each render
  // (its threads: the list below).
  SessionOptions session;
  std::vector<std::string> scenes;
  std::vector<int> threads;            // in the order each round runs them; empty: 1 and all cores
  int repeat = 5;                      // rounds
  std::string jsonPath;                // empty: defaultBenchJson(scenes)
  // Told on the bench's own thread as each render or control pass starts and ends.
  std::function<void(size_t done, size_t total, const std::string& item, const char* phase, double seconds)> progress;
};

// One measured render (or control pass: time.total only) and its CPU time.
struct BenchSample {
  int threads = 1;
  int round = 0;  // 0-based
  Timings time;
  CpuTiming cpu;
};

struct SceneBench {
  std::string path, name;
  std::string settings;              // "800x500, 4 spp, classic"
  std::vector<BenchSample> samples;  // in the order they ran
};

struct BenchOutcome {
  std::vector<int> threads;
  int repeat = 0;
  std::vector<std::string> overrides;
  std::vector<SceneBench> scenes;
  std::vector<BenchSample> control;  // the compute-only control, the same rounds
  CpuTiming whole;                   // the whole bench, validation included
  std::string jsonPath;
  std::vector<std::string> notes;    // the scenes' load notes; contended times
};

// "1,2" into thread counts, each 1..`cores` (0: the cores this process may use)
// and given once; InputError otherwise.
std::vector<int> parseThreadCounts(const std::string& list, int cores = 0);

// The JSON's place when --json is not given: a cache folder outside any checkout or
// scene folder ($XDG_CACHE_HOME or ~/.cache, then penumbra/bench), named after the
// first scene and the time, created if missing.
std::string defaultBenchJson(const std::vector<std::string>& scenes);

// Every scene loaded, planned and admitted and the JSON path checked against their
// inputs (InputError before any render), then `repeat` rounds of every scene at
// every thread count and the control at every thread count.
BenchOutcome runBench(const BenchRequest& request);

}  // namespace penumbra
