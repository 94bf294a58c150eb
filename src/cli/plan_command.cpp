// The plan subcommand: load, decide, print; nothing is emitted or rendered (the BVH is
// built only for the light split of photon passes).
#include "cli/plan_command.h"
#include "core/error.h"
#include "plan/memory_limit.h"
#include "plan/render_frame.h"
#include "plan/transport_model.h"
#include "io/scene_defaults.h"
#include "io/scene_loader.h"
#include <fmt/format.h>
#include <algorithm>
#include <cstdlib>
#include <iostream>

namespace penumbra {

namespace {

// What loading adds to a glTF scene, or would add without --no-defaults; "" when the
// scene lacks nothing (or is not a glTF file).
std::string defaultsLine(const LoadReport& load) {
  if (!load.noCamera && !load.noLight) return "";
  std::vector<std::string> parts;
  if (load.noCamera) parts.push_back("a camera framing the bounds (the file has none)");
  if (load.noLight) parts.push_back("a neutral sky (the file has no light)");
  const bool added = load.framedCamera || load.defaultSky;
  std::string line = added ? "  adds " : "  would add ";
  for (size_t i = 0; i < parts.size(); ++i) line += (i ? " and " : "") + parts[i];
  return line + (added ? "; --no-defaults keeps the file as it is\n" : " without --no-defaults\n");
}

}  // namespace

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
  addDefaultsOption(command, args.noDefaults);
}

namespace {
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
}  // namespace

void addBudgetOptions(CLI::App& command, RenderBudget& budget) {
  command.add_option("--time-limit", budget.seconds,
                     "Run progressive passes (at least 2) until this many seconds of the job have passed, then "
                     "write the image; --stats names the passes done")
      ->check(budgetValue(&RenderBudget::seconds));
  command.add_option("--target-error", budget.targetError,
                     "Run progressive passes (at least 2) until the estimated noise RMSE is at most this")
      ->check(budgetValue(&RenderBudget::targetError));
}

void addDefaultsOption(CLI::App& command, bool& noDefaults) {
  command.add_flag("--no-defaults", noDefaults,
                   "Load a .gltf/.glb scene as it is: no camera framing a model that has none, no neutral sky "
                   "for a model without lights");
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

PlanCommand::PlanCommand(CLI::App& app) {
  command_ = app.add_subcommand("plan", "Print what a render would run, and why, without rendering");
  command_->add_option("scene", scene_, "Scene file (JSON)")->required();
  command_->add_option("--aov", aov_, "View (default: the scene's render.aov)");
  command_->add_option("-D,--set", overrides_, "Override a scene value")->take_all()->allow_extra_args(false);
  command_->add_flag("--json", json_, "Print the plan as JSON (as in --stats)");
  addPlanOptions(*command_, planArgs_);
}

int PlanCommand::run() {
  const PlanOverrides passes = planArgs_.passes();
  std::vector<std::string> overrides = overrides_;
  if (!planArgs_.gateSetting().empty()) overrides.push_back(planArgs_.gateSetting());
  Scene scene = loadScene(scene_, overrides, loadLimits(0), planArgs_.load());
  const Aov aov = parseAov(aov_.empty() ? scene.render.aov : aov_);
  RenderPlan plan = makePlan(scene, aov, passes);
  // The light split needs a few rays per light: build the BVH only when a photon
  // pass could be split (no textures, no photons, no render).
  const bool split = plan[Pass::IndirectPhotons].on || plan[Pass::GlobalPhotons].on || plan[Pass::CausticPhotons].on;
  if (split) {
    const SceneAssets assets = prepareAssets(scene, false);
    splitByReach(plan, scene, *assets.tracer);
  }
  std::cout << (json_ ? planJson(plan) + "\n" : planText(plan));
  return 0;
}

CheckCommand::CheckCommand(CLI::App& app) {
  command_ = app.add_subcommand("check", "Validate scene files (every value, mesh and texture) without rendering");
  command_->add_option("scenes", scenes_, "Scene files")->required();
  command_->add_option("-D,--set", overrides_, "Override a scene value")->take_all()->allow_extra_args(false);
  addDefaultsOption(*command_, noDefaults_);
}

int CheckCommand::run() {
  for (const std::string& path : scenes_) {
    const Scene s = loadScene(path, overrides_, loadLimits(0), LoadOptions{!noDefaults_});
    const LoadReport& load = s.load;
    size_t triangles = 0;
    for (const TriangleMesh& m : s.meshes) triangles += m.triangles.size();
    // The file's own lights: the default sky is reported below as an addition.
    const size_t lights = s.lights.size() - (load.defaultSky ? 1 : 0);
    std::cout << path << ": ok (" << transportOf(s).name() << ", "
              << s.meshes.size() << " meshes with " << triangles << " triangles, " << s.spheres.size()
              << " spheres, " << lights << " lights, " << s.materials.size() << " materials)\n";
    // Where the geometry is: what a camera must frame (a model's units are its own).
    const SceneBounds b = sceneBounds(s);
    if (!b.empty()) {
      const Vec3 lo = b.lo, hi = b.hi;
      std::cout << "  bounds " << fmt::format("[{:g}, {:g}, {:g}] .. [{:g}, {:g}, {:g}]", lo.x, lo.y, lo.z, hi.x, hi.y, hi.z)
                << " (size " << fmt::format("{:g} x {:g} x {:g}", hi.x - lo.x, hi.y - lo.y, hi.z - lo.z) << ")\n";
    }
    std::cout << defaultsLine(load);
    for (const std::string& note : load.notes) std::cerr << "note: " << note << "\n";
  }
  return 0;
}

}  // namespace penumbra
