// `penumbra sweep SCENE -o DIR`: the command line of plan/sweep/sweep_run.h.
#pragma once
#include <CLI/CLI.hpp>
#include <memory>

namespace penumbra {

class SweepCommand {
 public:
  // Adds the `sweep` subcommand and its options to `app`.
  explicit SweepCommand(CLI::App& app);
  ~SweepCommand();
  bool selected() const;
  // Runs the sweep; returns the exit code (InputError propagates to main).
  int run();

 private:
  struct Options;
  std::unique_ptr<Options> o_;
};

}  // namespace penumbra
