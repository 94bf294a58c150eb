// `penumbra batch JOBS.json` and `penumbra batch SCENE... -o DIR`: the command
// line of plan/batch/batch_run.h, with shards for splitting a batch across processes.
#pragma once
#include <CLI/CLI.hpp>
#include <memory>

namespace penumbra {

class BatchCommand {
 public:
  explicit BatchCommand(CLI::App& app);
  ~BatchCommand();
  bool selected() const;
  // Exit code: 0 when every job rendered or was up to date, 1 when any failed.
  int run();

 private:
  struct Options;
  std::unique_ptr<Options> o_;
};

}  // namespace penumbra
