// `penumbra bench SCENE... --threads 1,2 --repeat 5`: the command line of
// cli/bench/bench_run.h; the table goes to stdout, the JSON to --json or the cache.
#pragma once
#include <CLI/CLI.hpp>
#include <memory>

namespace penumbra {

class BenchCommand {
 public:
  explicit BenchCommand(CLI::App& app);
  ~BenchCommand();
  bool selected() const;
  int run();

 private:
  struct Options;
  std::unique_ptr<Options> o_;
};

}  // namespace penumbra
