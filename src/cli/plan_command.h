// `penumbra plan SCENE` and `penumbra check SCENE`: the plan, or a validation,
// without rendering; and the
// --enable / --disable PASS options that render and plan share.
#pragma once
#include "plan/render_plan.h"
#include <CLI/CLI.hpp>
#include <string>
#include <vector>

namespace penumbra {

// Adds --enable PASS and --disable PASS (repeatable) to a subcommand.
void addPassOptions(CLI::App& command, std::vector<std::string>& enable, std::vector<std::string>& disable);
// The overrides those options name; throws InputError for an unknown pass.
PlanOverrides passOverrides(const std::vector<std::string>& enable, const std::vector<std::string>& disable);

class PlanCommand {
 public:
  explicit PlanCommand(CLI::App& app);
  bool selected() const { return command_->parsed(); }
  int run();

 private:
  CLI::App* command_ = nullptr;
  std::string scene_, aov_;
  std::vector<std::string> overrides_, enable_, disable_;
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
};

}  // namespace penumbra
