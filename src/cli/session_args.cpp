// The registry is the only place a shared option is declared, its help written and
// its value checked; the commands read the parsed values from SessionArgs.
#include "cli/session_args.h"
#include "core/error.h"
#include "plan/memory_limit.h"
#include <fmt/format.h>
#include <algorithm>
#include <cstdlib>

namespace penumbra {
namespace {

void addDefaultsOption(CLI::App& command, PlanArgs& args) {
  command.add_flag("--no-defaults", args.noDefaults,
                   "Load a .gltf/.glb scene as it is: no camera framing a model that has none, no studio environment "
                   "for a model without lights");
  command.add_option("--camera", args.camera,
                     "auto: frame the model (its bounding sphere fills 90% of the image's smaller side) even when "
                     "the file has cameras; NAME or INDEX (0-based, as in the glTF file's \"cameras\"): use that "
                     "camera (default: the file's first camera, else framed)")
      ->type_name("auto|NAME|INDEX")
      ->check(CLI::Validator([](std::string& v) { return v.empty() ? std::string("must not be empty") : ""; }, ""));
}

void addPlanOptions(CLI::App& command, PlanArgs& args) {
  command.add_option("--enable", args.enable, "Force a pass on (see penumbra plan): gate, indirect-photons, "
                                              "global-photons, caustic-photons, shadow-rays, reflection, refraction, "
                                              "textures, light-samples, packets, precompute")
      ->take_all()->allow_extra_args(false);
  command.add_option("--disable", args.disable, "Force a pass off (an override that changes the image is said so)")
      ->take_all()->allow_extra_args(false);
  command.add_option("--gate", args.gate, "The shadow gate: on, off or auto (default: the scene's photons.gate, else auto)")
      ->check(CLI::IsMember({"on", "off", "auto"}));
  command.add_flag("--no-gate", args.noGate, "Cast every shadow ray instead of asking the shadow photon map (--gate off)");
  command.add_option("--adaptive", args.adaptive,
                     "Adaptive pixel sampling: from pass 3 on, pixels whose error is high take more camera samples "
                     "(render.adaptive; default: the scene's, else off)")
      ->check(CLI::IsMember({"on", "off"}));
  addDefaultsOption(command, args);
}

// A budget value as checkBudget takes it; an empty one is a mistake, not "no budget".
CLI::Validator budgetValue(double RenderBudget::*field) {
  return CLI::Validator(
      [field](std::string& text) -> std::string {
        RenderBudget b;
        char* end = nullptr;
        b.*field = std::strtod(text.c_str(), &end);
        if (text.empty() || *end != '\0') return "'" + text + "' is not a number";
        try {
          checkBudget(b);
        } catch (const InputError& e) {
          const std::string why = e.what();  // "--time-limit: ...": CLI11 names the option itself
          return why.substr(why.find(": ") + 2);
        }
        return "";
      },
      "NUMBER >= 0");
}

void addBudgetOptions(CLI::App& command, RenderBudget& budget) {
  command.add_option("--time-limit", budget.seconds,
                     "Run progressive passes (at least 2) until this many seconds of the job have passed, then "
                     "write the image; --stats names the passes done")
      ->check(budgetValue(&RenderBudget::seconds));
  command.add_option("--target-error", budget.targetError,
                     "Run progressive passes (at least 4) until the estimated noise and photon-map bias together, "
                     "sqrt(noise^2 + bias^2), are at most this RMSE (of --target-error-of)")
      ->check(budgetValue(&RenderBudget::targetError));
  command.add_option_function<std::string>(
             "--target-error-of", [&budget](const std::string& name) { budget.figure = parseErrorFigure(name); },
             "The figure --target-error aims at: lighting (default: pixels that see no emitter) or image")
      ->check(CLI::IsMember(std::vector<std::string>(kErrorFigureNames.begin(), kErrorFigureNames.end())));
  command.add_option_function<std::string>(
             "--target-bias", [&budget](const std::string& name) { budget.bias = parseBiasFigure(name); },
             "The photon-map bias --target-error counts: counted (default: what stands out of its noise) or "
             "bound (what noise may hide too, where the gathers probe their bias)")
      ->check(CLI::IsMember(std::vector<std::string>(kBiasFigureNames.begin(), kBiasFigureNames.end())));
}

void addDisplayOptions(CLI::App& command, SessionArgs& args) {
  command.add_option("--exposure", args.displayValues.exposure, "PNG: multiply by 2^EV before the tone curve (default 0)")
      ->check(CLI::Range(-64.0, 64.0));
  command.add_option("--tonemap", args.tonemap,
                     "PNG tone curve: clamp (a JSON scene's default), reinhard, filmic or neutral (Khronos PBR "
                     "Neutral, a glTF/OBJ model's default); EXR stays linear")
      ->check(CLI::IsMember({"clamp", "reinhard", "filmic", "neutral"}));
}

}  // namespace

DisplayOptions SessionArgs::display() const {
  DisplayOptions d = displayValues;
  if (!tonemap.empty()) {
    d.tone = parseToneMap(tonemap);
    d.toneAsked = true;
  }
  return d;
}

PlanOverrides PlanArgs::passes() const {
  PlanOverrides o;
  for (const std::string& e : enable) o.enable.push_back(parsePass(e));
  for (const std::string& d : disable) o.disable.push_back(parsePass(d));
  for (Pass e : o.enable) {
    for (Pass d : o.disable) {
      if (e == d) throw InputError(std::string("--enable and --disable both name ") + passName(e));
    }
  }
  auto names = [&](const std::vector<Pass>& list) { return std::find(list.begin(), list.end(), Pass::Gate) != list.end(); };
  const std::string mode = noGate ? "off" : gate;
  if (noGate && !gate.empty() && gate != "off") throw InputError("--no-gate contradicts --gate " + gate);
  if (names(o.enable) && mode == "off") throw InputError(std::string(noGate ? "--no-gate" : "--gate off") + " contradicts --enable gate");
  if (names(o.disable) && mode == "on") throw InputError("--gate on contradicts --disable gate");
  return o;
}

std::string PlanArgs::gateSetting() const {
  const std::string mode = noGate ? "off" : gate;
  return mode.empty() ? "" : "photons.gate=" + mode;
}

std::string PlanArgs::adaptiveSetting() const {
  return adaptive.empty() ? "" : std::string("render.adaptive=") + (adaptive == "on" ? "true" : "false");
}

int SessionArgs::threadCount() const {
  if (threads.empty()) return 0;
  char* end = nullptr;
  const long n = std::strtol(threads.c_str(), &end, 10);
  if (*end != '\0' || n < 1 || n > 1024) {
    throw InputError("--threads: expected one thread count in 1..1024, got '" + threads + "'");
  }
  return static_cast<int>(n);
}

uint64_t SessionArgs::maxMemoryBytes() const { return maxMemory.empty() ? 0 : parseMemorySize(maxMemory); }

SessionOptions SessionArgs::options(const std::vector<std::string>& own) const {
  SessionOptions o;
  o.threads = threadList ? 0 : threadCount();
  o.plan = plan.passes();
  o.load = plan.load();
  o.maxMemoryBytes = maxMemoryBytes();
  o.budget = budget;
  o.mapDir = mapDir;
  o.force = force;
  o.overrides = overrides;
  o.overrides.insert(o.overrides.end(), own.begin(), own.end());
  if (!plan.gateSetting().empty()) o.overrides.push_back(plan.gateSetting());
  if (!plan.adaptiveSetting().empty()) o.overrides.push_back(plan.adaptiveSetting());
  return o;
}

void addSessionOptions(CLI::App& command, SessionArgs& args, unsigned which, const char* each,
                       const char* threadsHelp) {
  if (which & kThreadsOption) {
    args.threadList = threadsHelp != nullptr;
    command.add_option("-t,--threads,--nthreads", args.threads,
                       threadsHelp ? threadsHelp : "Worker threads (default: all cores)");
  }
  if (which & kMaxMemoryOption) {
    command.add_option("--max-memory", args.maxMemory,
                       fmt::format("Refuse (exit 2) a {} estimated to need more, e.g. 8G, 512M (default: the memory "
                                   "available when it starts)", *each ? each : "render"));
  }
  if (which & kSetOption) {
    command.add_option("-D,--set", args.overrides,
                       fmt::format("Override a scene value{}{}, e.g. --set render.max_depth=8 -D objects[0].radius=2",
                                   *each ? " in every " : "", each))
        ->take_all()
        ->allow_extra_args(false);
  }
  if (which & kQuietOption) command.add_flag("-q,--quiet", args.quiet, "No progress, notes or summary on stderr");
  if (which & kPlanOption) addPlanOptions(command, args.plan);
  if (which & kDefaultsOption) addDefaultsOption(command, args.plan);
  if (which & kBudgetOption) addBudgetOptions(command, args.budget);
  if (which & kMapDirOption) {
    command.add_option("--map-dir", args.mapDir,
                       "Photon map files: load each photon stage from DIR by its key, or build it and write it "
                       "there for the next process (created if missing; see docs/photon-maps.md)")
        ->type_name("DIR");
  }
  if (which & kForceOption) {
    command.add_flag("--force", args.force,
                     *each ? fmt::format("Render every {}, even those whose outputs are up to date, from pass 1: "
                                         "discard the passes an interrupted {} saved (OUTPUT.passes)", each, each)
                           : std::string("Render from pass 1: discard the passes an interrupted render saved "
                                         "(OUTPUT.passes)"));
  }
  if (which & kDisplayOption) addDisplayOptions(command, args);
}

}  // namespace penumbra
