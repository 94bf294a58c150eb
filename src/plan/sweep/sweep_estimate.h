// What a sweep will cost before it starts: every run's own estimate (plan/resource_estimate.h)
// put together as the sweep will spend it, knowing what the runs share, so the figure it
// announces and its ETA are the sweep's and not the sum of lone renders.
#pragma once
#include <string>
#include <vector>

namespace penumbra {

struct PlannedJob;

// Seconds on the session's threads.
struct SweepEstimate {
  double reference = 0.0;  // the sweep's own long reference (0: given, reloaded, or a run)
  double bvh = 0.0;        // one build per geometry
  double photons = 0.0;    // each budget's pass-0 photons and maps once, every later pass's per run
  double frames = 0.0;     // every run's frames: --repeat and the gate's ungated render included
  // Each run's share of bvh + photons + frames, by run index (0 for a run not rendered),
  // what the ETA counts as done when the run is.
  std::vector<double> runs;
  // How much longer the wall time will be on a machine whose other work holds its
  // cores (busyStretch); 1 on a quiet one.
  double stretch = 1.0;
  double seconds() const { return reference + bvh + photons + frames; }
};

// A thread's wait on a machine with `load` runnable tasks (the 1-minute load
// average) and `cores` cores, once `threads` more join them: fair scheduling gives
// each a share cores / (load + threads) of a core, so the wall time stretches by its
// inverse (at least 1). Unknown load or cores: 1.
double busyStretch(double load, int cores, int threads);

struct SweepEstimateInput {
  std::vector<const PlannedJob*> runs;  // by run index, prepared; null: not rendered by this sweep
  const PlannedJob* reference = nullptr;  // the highest run, when the sweep renders its long reference
  int referencePasses = 1;  // ... with this many times its passes
  int repeat = 1;
  bool compareGate = true;
};

SweepEstimate estimateSweep(const SweepEstimateInput& input);

// "sweep: 18 runs to render, estimated ~3 min on 2 threads (reference ~2 min, photons ~12 s,
// frames ~40 s)", and with a stretch above 1.5 "; the machine is busy (load 9.8 on 2
// cores): ~16 min".
std::string describeSweepEstimate(const SweepEstimate& e, size_t runs, int threads, double load = -1.0,
                                  int cores = 0);

}  // namespace penumbra
