// `penumbra batch JOBS.json` and `penumbra batch SCENE... -o DIR`: the command
// line of plan/batch/batch_run.h, with shards for splitting a batch across processes.
#pragma once
#include <CLI/CLI.hpp>
#include <memory>

namespace penumbra {

// A batch whose jobs were all checked but some failed while rendering (the others
// finished): not 1, the internal-error code, so a scheduler's retry policy can tell them apart.
inline constexpr int kExitJobsFailed = 3;
// `batch --status`: some job is missing, stale or failed to load.
inline constexpr int kExitNotUpToDate = 4;

class BatchCommand {
 public:
  explicit BatchCommand(CLI::App& app);
  ~BatchCommand();
  bool selected() const;
  // Exit code: 0 when every job rendered or was up to date, kExitJobsFailed when any
  // failed; with --status, kExitNotUpToDate unless all are up to date.
  int run();

 private:
  struct Options;
  std::unique_ptr<Options> o_;
};

}  // namespace penumbra
