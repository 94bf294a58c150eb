// `penumbra plan SCENE` and `penumbra check SCENE`: the plan, or a validation,
// without rendering.
#pragma once
#include "cli/session_args.h"
#include <CLI/CLI.hpp>
#include <string>
#include <vector>

namespace penumbra {

class PlanCommand {
 public:
  explicit PlanCommand(CLI::App& app);
  bool selected() const { return command_->parsed(); }
  int run();

 private:
  CLI::App* command_ = nullptr;
  std::string scene_, aov_;
  SessionArgs args_;  // -D and the plan options
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
  std::vector<std::string> scenes_;
  SessionArgs args_;  // -D and --no-defaults
};

}  // namespace penumbra
