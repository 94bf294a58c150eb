// penumbra sweep's grid: the command line's value lists (--photons, --k, --depth,
// --spp, --vary KEY=...) expanded into runs, each a set of --set overrides, and
// the run at every knob's highest value (the default reference).
#pragma once
#include "core/scene.h"
#include "plan/transport_model.h"
#include <string>
#include <vector>

namespace penumbra {

struct SweepKnob {
  std::string name;                 // "photons", "k", "depth", "spp", or a scene key
  std::vector<std::string> values;  // as the user wrote them ("1e4"), in order
  std::vector<std::string> keys;    // the scene keys each value is written to
};

struct SweepRun {
  std::string id;                      // "photons=1e4 k=10 depth=1 spp=1": the row's key
  std::string slug;                    // a file name made of the id
  std::vector<std::string> values;     // one per knob
  std::vector<std::string> overrides;  // the sweep's --set, then this run's knobs
};

struct SweepSpec {
  std::vector<SweepKnob> knobs;
  std::vector<SweepRun> runs;  // every combination, the last knob varying fastest
  size_t highest = 0;          // the run with every knob at its highest value
};

// "1e4,1e5" -> {"1e4", "1e5"}; throws InputError naming `option` on an empty item.
std::vector<std::string> splitValues(const std::string& list, const std::string& option);

// A named knob for the scene's model: photons -> photons.indirect (classic) or
// photons.global and photons.caustic (physical); k -> photons.k_indirect or
// photons.k_global and photons.k_caustic; depth -> render.max_depth; spp -> camera.spp.
// A scene with `media` varies its volume map's photons.volume and photons.k_volume too.
SweepKnob namedKnob(const std::string& name, const std::string& list, const TransportModel& model,
                    bool media = false);
// --vary KEY=v1,v2: any scene key.
SweepKnob keyKnob(const std::string& arg);

// --threads 1,2: worker threads, a knob that writes no scene key (each count's runs
// render in a session of that many workers). Throws InputError for a value outside 1..1024.
inline constexpr const char* kThreadsKnob = "threads";
SweepKnob threadsKnob(const std::string& list);
// The run's value of the threads knob, 0 without one.
int runThreads(const SweepSpec& spec, const SweepRun& run);
// The threads knob's values, the most first; empty without one.
std::vector<int> threadCounts(const SweepSpec& spec);

// The grid. Throws InputError for no knob, a knob given twice, or over `maxRuns` runs.
SweepSpec expandGrid(std::vector<SweepKnob> knobs, const std::vector<std::string>& baseOverrides,
                     size_t maxRuns = 4096);

// A value as the JSON text for --set: integral numbers written as integers
// ("1e4" -> "10000", since photon counts are integers), anything else unchanged.
std::string overrideValue(const std::string& value);

}  // namespace penumbra
