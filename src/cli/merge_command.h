// `penumbra merge PART... -o FRAME`: the parts of a tiled render into one frame.
#pragma once
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
  bool quiet_ = false;
};

}  // namespace penumbra
