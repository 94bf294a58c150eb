// The plan and check subcommands: load, decide (or validate), print; nothing is emitted
// or rendered (the BVH is built only for the light split of photon passes).
#include "cli/plan_command.h"
#include "core/error.h"
#include "plan/check_report.h"
#include "plan/command_support.h"
#include "plan/memory_limit.h"
#include "plan/render_frame.h"
#include "plan/transport_model.h"
#include <iostream>

namespace penumbra {

PlanCommand::PlanCommand(CLI::App& app) {
  command_ = app.add_subcommand("plan", "Print what a render would run, and why, without rendering");
  command_->add_option("scene", scene_, "Scene file (JSON)")->required();
  command_->add_option("--aov", aov_, "View (default: the scene's render.aov)");
  command_->add_flag("--json", json_, "Print the plan as JSON (as in --stats)");
  addSessionOptions(*command_, args_, kSetOption | kPlanOption, "");
}

int PlanCommand::run() {
  const SessionOptions options = args_.options();
  Scene scene = loadJobScene(scene_, options);
  const Aov aov = parseAov(aov_.empty() ? scene.render.aov : aov_);
  RenderPlan plan = makePlan(scene, aov, options.plan);
  // The light split needs a few rays per light: build the BVH only when a photon
  // pass could be split (no textures, no photons, no render).
  const bool split = plan[Pass::IndirectPhotons].on || plan[Pass::GlobalPhotons].on || plan[Pass::CausticPhotons].on;
  if (split) {
    const SceneAssets assets = prepareAssets(scene);
    splitByReach(plan, scene, *assets.tracer);
  }
  std::cout << (json_ ? planJson(plan) + "\n" : planText(plan));
  return 0;
}

CheckCommand::CheckCommand(CLI::App& app) {
  command_ = app.add_subcommand("check", "Validate scene files (every value, mesh and texture) without rendering");
  command_->add_option("scenes", scenes_, "Scene files")->required();
  addSessionOptions(*command_, args_, kSetOption | kDefaultsOption, "");
}

int CheckCommand::run() {
  const SessionOptions options = args_.options();
  for (const std::string& path : scenes_) {
    const Scene s = loadJobScene(path, options);
    std::cout << path << ": " << checkReport(s);
    for (const std::string& note : s.load.notes) std::cerr << noteLine(note) << "\n";
  }
  return 0;
}

}  // namespace penumbra
