// Options of `penumbra bench`, its progress line, and where the results go.
#include "cli/bench_command.h"
#include "cli/plan_command.h"
#include "cli/progress_line.h"
#include "cli/progress_meter.h"
#include "plan/bench_report.h"
#include "plan/bench_run.h"
#include "plan/memory_limit.h"
#include "io/temp_file.h"
#include <iostream>
#include <optional>

namespace penumbra {

struct BenchCommand::Options {
  CLI::App* command = nullptr;
  std::vector<std::string> scenes, overrides;
  std::string threads, json, maxMemory;
  int repeat = 5;
  PlanArgs plan;
  bool quiet = false;
};

BenchCommand::BenchCommand(CLI::App& app) : o_(std::make_unique<Options>()) {
  Options& o = *o_;
  o.command = app.add_subcommand("bench", "Time your scenes at several thread counts beside a compute-only control");
  CLI::App* c = o.command;
  c->add_option("scenes", o.scenes, "Scene files (JSON, .gltf or .glb)")->required();
  c->add_option("-t,--threads,--nthreads", o.threads, "Thread counts, interleaved in each round (default: 1 and all cores)");
  c->add_option("--repeat", o.repeat, "Rounds: renders per scene and thread count (default 5)");
  c->add_option("--json", o.json, "Write every sample as JSON here (default: a new file in ~/.cache/penumbra/bench)");
  c->add_option("-D,--set", o.overrides, "Override a scene value in every render")->take_all()->allow_extra_args(false);
  c->add_option("--max-memory", o.maxMemory, "Refuse (exit 2) a scene estimated to need more, e.g. 8G");
  addPlanOptions(*c, o.plan);
  c->add_flag("-q,--quiet", o.quiet, "No progress line and no notes (the table still prints)");
}

BenchCommand::~BenchCommand() = default;
bool BenchCommand::selected() const { return o_->command->parsed(); }

int BenchCommand::run() {
  Options& o = *o_;
  BenchRequest req;
  req.plan = o.plan.passes();  // contradicting options: refused before any scene is read
  req.load = o.plan.load();
  req.scenes = o.scenes;
  req.overrides = o.overrides;
  if (!o.plan.gateSetting().empty()) req.overrides.push_back(o.plan.gateSetting());
  if (!o.threads.empty()) req.threads = parseThreadCounts(o.threads);
  req.repeat = o.repeat;
  req.jsonPath = o.json;
  if (!o.maxMemory.empty()) req.maxMemoryBytes = parseMemorySize(o.maxMemory);
  std::optional<ItemProgress> progress;
  if (!o.quiet) {
    progress.emplace();
    req.phases = progress->phases();
    req.progress = [&](size_t done, size_t total, const std::string& item, const char* phase, double seconds) {
      progress->line(progressLine("bench", done, total, item, phase, seconds, done, total - done));
    };
  }
  const BenchOutcome out = runBench(req);
  if (progress) progress->finish();
  writeTextFileAtomic(out.jsonPath, benchJson(out));
  std::cout << benchTable(out);
  if (!o.quiet) {
    for (const std::string& n : out.notes) std::cerr << "note: " << n << "\n";
    std::cerr << "wrote " << out.jsonPath << "\n";
  }
  return 0;
}

}  // namespace penumbra
