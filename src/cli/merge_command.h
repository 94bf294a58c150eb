// `penumbra merge PART... -o FRAME`: the parts of a tiled render into one frame.
#pragma once
#include "cli/session_args.h"
#include <CLI/CLI.hpp>
#include <string>
#include <vector>

namespace penumbra {

class MergeCommand {
 public:
  explicit MergeCommand(CLI::App& app);
  bool selected() const { return command_->parsed(); }
  int run();

 private:
  CLI::App* command_ = nullptr;
  std::vector<std::string> parts_;
  std::string output_;
  SessionArgs args_;  // -q, --exposure, --tonemap
};

}  // namespace penumbra
