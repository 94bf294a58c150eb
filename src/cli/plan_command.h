// `penumbra plan SCENE` and `penumbra check SCENE`: the plan, or a validation,
// without rendering; and the
// --enable / --disable PASS options that render and plan share.
#pragma once
#include "io/scene_loader.h"
#include "plan/render_budget.h"
#include "plan/render_plan.h"
#include <CLI/CLI.hpp>
#include <string>
#include <vector>

namespace penumbra {

// The options every rendering command shares about the plan: --enable PASS and
// --disable PASS (repeatable), --gate MODE and --no-gate; and about loading:
// --no-defaults.
struct PlanArgs {
  std::vector<std::string> enable, disable;
  std::string gate;     // on, off, auto; empty: the scene's photons.gate
  bool noGate = false;  // --no-gate: --gate off
  bool noDefaults = false;  // --no-defaults: a glTF scene gets no framed camera or default sky
  LoadOptions load() const { return LoadOptions{!noDefaults}; }
  // The passes named; throws InputError for an unknown pass, or when two of these
  // options contradict each other (--no-gate --gate on, --enable gate --no-gate, ...).
  PlanOverrides passes() const;
  // The photons.gate override --gate or --no-gate ask for ("photons.gate=off"); empty: none.
  std::string gateSetting() const;
};
void addPlanOptions(CLI::App& command, PlanArgs& args);
// --time-limit and --target-error (render, batch and sweep: for each job).
void addBudgetOptions(CLI::App& command, RenderBudget& budget);
// --no-defaults alone (check has no plan options).
void addDefaultsOption(CLI::App& command, bool& noDefaults);

class PlanCommand {
 public:
  explicit PlanCommand(CLI::App& app);
  bool selected() const { return command_->parsed(); }
  int run();

 private:
  CLI::App* command_ = nullptr;
  std::string scene_, aov_;
  std::vector<std::string> overrides_;
  PlanArgs planArgs_;
  bool json_ = false;
};

// `penumbra check SCENE`: loads and validates (textures included) without
// rendering; one line per scene, exit 2 on the first bad one.
class CheckCommand {
 public:
  explicit CheckCommand(CLI::App& app);
  bool selected() const { return command_->parsed(); }
  int run();

 private:
  CLI::App* command_ = nullptr;
  std::vector<std::string> scenes_, overrides_;
  bool noDefaults_ = false;
};

}  // namespace penumbra
