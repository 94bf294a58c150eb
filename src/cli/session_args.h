// The options the commands share, registered once: threads, memory, scene overrides,
// quiet, the plan's overrides (--enable/--disable/--gate/--no-gate), loading
// (--no-defaults, --camera), budgets (--time-limit/--target-error), map files (--map-dir) and --force. Each command asks for its set.
#pragma once
#include "plan/pipeline.h"
#include "plan/session_options.h"
#include <CLI/CLI.hpp>
#include <cstdint>
#include <string>
#include <vector>

namespace penumbra {

// --enable PASS and --disable PASS (repeatable), --gate MODE and --no-gate; --no-defaults, --camera.
struct PlanArgs {
  std::vector<std::string> enable, disable;
  std::string gate;     // on, off, auto; empty: the scene's photons.gate
  bool noGate = false;  // --no-gate: --gate off
  std::string adaptive;  // --adaptive on|off; empty: the scene's render.adaptive
  bool noDefaults = false;  // --no-defaults: a glTF scene gets no framed camera or default sky
  std::string camera;       // --camera auto|NAME|INDEX (LoadOptions::camera)
  LoadOptions load() const {
    LoadOptions o;
    o.defaults = !noDefaults;
    o.camera = camera;
    return o;
  }
  // The passes named; throws InputError for an unknown pass, or when two of these
  // options contradict each other (--no-gate --gate on, --enable gate --no-gate, ...).
  PlanOverrides passes() const;
  // The photons.gate override --gate or --no-gate ask for ("photons.gate=off"); empty: none.
  std::string gateSetting() const;
  // The render.adaptive override --adaptive asks for ("render.adaptive=true"); empty: none.
  std::string adaptiveSetting() const;
};

// Which shared options a command takes (addSessionOptions).
enum SessionOption : unsigned {
  kThreadsOption = 1u << 0,    // -t/--threads/--nthreads
  kMaxMemoryOption = 1u << 1,  // --max-memory
  kSetOption = 1u << 2,        // -D/--set
  kQuietOption = 1u << 3,      // -q/--quiet
  kPlanOption = 1u << 4,       // --enable, --disable, --gate, --no-gate, --adaptive, --no-defaults, --camera
  kDefaultsOption = 1u << 5,   // --no-defaults and --camera alone (check: no plan)
  kBudgetOption = 1u << 6,     // --time-limit, --target-error
  kMapDirOption = 1u << 7,     // --map-dir
  kForceOption = 1u << 8,      // --force: discard saved passes (batch: and render up-to-date jobs)
  kDisplayOption = 1u << 9,    // --exposure, --tonemap (a PNG's display transform)
};

struct SessionArgs {
  std::string threads;  // as given: one count, or a list where the command takes one (sweep, bench)
  bool threadList = false;  // -t takes a list (addSessionOptions with threadsHelp): the command reads it
  std::string maxMemory;
  std::vector<std::string> overrides;  // -D, in order
  bool quiet = false;
  PlanArgs plan;
  RenderBudget budget;
  std::string mapDir;  // --map-dir: photon map files are loaded from and written to it
  bool force = false;
  DisplayOptions displayValues;  // --exposure; the tone curve is `tonemap`'s
  std::string tonemap;
  // --exposure and --tonemap for a PNG output (default: exposure 0, the scene's curve: io/tone_map.h sceneDisplay).
  DisplayOptions display() const;
  // The one thread count of -t (0: all cores); a list or a count outside 1..1024 is refused.
  int threadCount() const;
  // --max-memory in bytes; 0: the memory available.
  uint64_t maxMemoryBytes() const;
  // Every job's options, checked (InputError): the thread count (0 where -t is a list),
  // memory, plan overrides, loading, budget, the map folder, and -D, then `own` (a command's options
  // that stand for scene values, e.g. render's --seed), then --gate and --adaptive.
  SessionOptions options(const std::vector<std::string>& own = {}) const;
};

// Registers the options in `which` on `command`. `each` names what one command
// renders ("job", "run", "render"): "Override a scene value in every job" ("": the
// scene the command reads); and
// `threadsHelp`, when not null, says what -t means for a command that takes a list.
void addSessionOptions(CLI::App& command, SessionArgs& args, unsigned which, const char* each,
                       const char* threadsHelp = nullptr);

}  // namespace penumbra
