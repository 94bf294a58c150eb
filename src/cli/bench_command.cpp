// Options of `penumbra bench`, its progress line, and where the results go.
#include "cli/bench_command.h"
#include "cli/session_args.h"
#include "cli/progress_line.h"
#include "cli/progress_meter.h"
#include "cli/bench/bench_report.h"
#include "cli/bench/bench_run.h"
#include "plan/memory_limit.h"
#include "plan/command_support.h"
#include <iostream>
#include <optional>

namespace penumbra {

struct BenchCommand::Options {
  CLI::App* command = nullptr;
  std::vector<std::string> scenes;
  SessionArgs session;
  std::string json;
  int repeat = 5;
};

BenchCommand::BenchCommand(CLI::App& app) : o_(std::make_unique<Options>()) {
  Options& o = *o_;
  o.command = app.add_subcommand("bench", "Time your scenes at several thread counts beside a compute-only control");
  CLI::App* c = o.command;
  c->add_option("scenes", o.scenes, "Scene files (JSON, .gltf or .glb)")->required();
  c->add_option("--repeat", o.repeat, "Rounds: renders per scene and thread count (default 5)");
  c->add_option("--json", o.json, "Write every sample as JSON here (default: a new file in ~/.cache/penumbra/bench)");
  addSessionOptions(*c, o.session, kThreadsOption | kMaxMemoryOption | kSetOption | kQuietOption | kPlanOption,
                    "render", "Thread counts, interleaved in each round (default: 1 and all cores)");
}

BenchCommand::~BenchCommand() = default;
bool BenchCommand::selected() const { return o_->command->parsed(); }

int BenchCommand::run() {
  Options& o = *o_;
  BenchRequest req;
  const SessionArgs& session = o.session;
  req.session = session.options();  // contradicting options: refused before any scene is read
  req.scenes = o.scenes;
  if (!session.threads.empty()) req.threads = parseThreadCounts(session.threads);
  req.repeat = o.repeat;
  req.jsonPath = o.json;
  std::optional<ItemProgress> progress;
  if (!session.quiet) {
    progress.emplace();
    req.session.progress = progress->phases();
    req.progress = [&](size_t done, size_t total, const std::string& item, const char* phase, double seconds) {
      progress->line(progressLine("bench", done, total, item, phase, seconds, done, total - done));
    };
  }
  const BenchOutcome out = runBench(req);
  if (progress) progress->finish();
  writeTextOutput(out.jsonPath, benchJson(out));
  std::cout << benchTable(out);
  if (!session.quiet) {
    for (const std::string& n : out.notes) std::cerr << noteLine(n) << "\n";
    std::cerr << "wrote " << out.jsonPath << "\n";
  }
  return 0;
}

}  // namespace penumbra
