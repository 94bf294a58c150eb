// Options of `penumbra batch`, the shard selection, the progress line and the summary.
#include "cli/batch_command.h"
#include "plan/batch/batch_jobs.h"
#include "cli/progress_line.h"
#include "plan/batch/batch_run.h"
#include "cli/session_args.h"
#include "cli/progress_meter.h"
#include "plan/cpu_report.h"
#include "plan/memory_limit.h"
#include "plan/sweep/sweep_spec.h"
#include "core/error.h"
#include <fmt/format.h>
#include <unistd.h>
#include <filesystem>
#include <optional>
#include <iostream>

namespace penumbra {

struct BatchCommand::Options {
  CLI::App* command = nullptr;
  std::vector<std::string> inputs;
  SessionArgs session;  // its budget is every job's
  std::string out, views, format = "png", shard, listShard, mapCache;
  bool keepGoing = false;
};

BatchCommand::BatchCommand(CLI::App& app) : o_(std::make_unique<Options>()) {
  Options& o = *o_;
  o.command = app.add_subcommand("batch", "Render many jobs in one process, sharing scenes and photon maps");
  CLI::App* c = o.command;
  c->add_option("inputs", o.inputs, "A jobs file (JSON with a \"jobs\" list, docs/batch.md) or scene files")->required();
  c->add_option("-o,--output", o.out, "Folder for the images of scene files given directly");
  c->add_option("--views", o.views, "Views of scene files given directly, e.g. beauty,depth (default: each scene's render.aov)");
  c->add_option("--format", o.format, "Image format of scene files given directly: png or exr (several views: one layered exr)")
      ->check(CLI::IsMember({"png", "exr"}));
  c->add_option("--shard", o.shard, "Render only shard I of N (1-based), e.g. 2/4");
  c->add_option("--list-shard", o.listShard, "Print the jobs shard I/N would take, and exit");
  c->add_option("--map-cache", o.mapCache,
                "Photon maps kept for later jobs, at most this much (LRU), e.g. 2G (default: " +
                    formatBytes(static_cast<double>(kStageCacheBytes)) + ")");
  c->add_flag("--keep-going", o.keepGoing, "Report a job that fails validation and go on");
  addSessionOptions(*c, o.session,
                    kThreadsOption | kMaxMemoryOption | kSetOption | kQuietOption | kPlanOption | kBudgetOption |
                        kForceOption,
                    "job");
}

BatchCommand::~BatchCommand() = default;
bool BatchCommand::selected() const { return o_->command->parsed(); }

namespace {

// The table printed after a batch: one line per job and the totals.
std::string batchSummary(const BatchOutcome& o) {
  std::string s = fmt::format("{:<24} {:>8} {:>8} {:>5}  {:<14} {:<12} {}\n", "job", "time", "cpu", "share", "reused",
                              "status", "output");
  for (const BatchJobResult& j : o.jobs) {
    const std::string status = j.status.size() > 60 ? j.status.substr(0, 57) + "..." : j.status;
    // A job that only checked its outputs ran too briefly for a share to mean anything.
    const std::string share = j.status == "rendered" ? fmt::format("{:.2f}", j.cpu.share) : "-";
    s += fmt::format("{:<24} {:>7.2f}s {:>7.2f}s {:>5}  {:<14} {:<12} {}\n", j.name, j.seconds, j.cpu.cpuSeconds,
                     share, j.reused.empty() ? "-" : j.reused, status, j.outputs.empty() ? "" : j.outputs.front());
  }
  s += fmt::format("{} jobs: {} rendered, {} up to date, {} failed in {:.1f} s; {}; scenes built {}, photon maps "
                   "built {} (reused {} times, {} evicted, cache peak {:.1f} MB)\n",
                   o.jobs.size(), o.rendered, o.upToDate, o.failed, o.seconds, cpuLine(o.cpu), o.sceneBuilds,
                   o.photonBuilds, o.photonReuses, o.evictions, o.peakCacheBytes / 1e6);
  return s;
}

}  // namespace

int BatchCommand::run() {
  Options& o = *o_;
  BatchRequest req;
  const SessionArgs& session = o.session;
  req.session = session.options();  // contradicting options: refused before any scene is read
  const std::string gate = session.plan.gateSetting();
  const bool jobsFile = o.inputs.size() == 1 && isJobsFile(o.inputs[0]);
  if (jobsFile) {
    req.jobs = readJobsFile(o.inputs[0]);
    // The command line's gate wins over a job's own photons.gate.
    if (!gate.empty()) for (BatchJob& j : req.jobs) j.overrides.push_back(gate);
    req.extraInputs.push_back(o.inputs[0]);
  } else {
    if (o.out.empty()) throw InputError("batch: -o DIR is required when scene files are given directly");
    std::error_code ec;
    std::filesystem::create_directories(o.out, ec);
    if (ec) throw InputError(o.out + ": cannot create the output folder (" + ec.message() + ")");
    req.jobs = jobsForScenes(o.inputs, o.out, o.views.empty() ? std::vector<std::string>{""} : splitValues(o.views, "--views"), "." + o.format);
  }
  const std::string shardArg = !o.listShard.empty() ? o.listShard : o.shard;
  if (!shardArg.empty()) {
    const auto [index, count] = parseShard(shardArg);
    req.shard = BatchShard{index, count};
    req.listShard = !o.listShard.empty();
  }
  req.force = session.force;
  req.keepGoing = o.keepGoing;
  if (!o.mapCache.empty()) req.session.stageCacheBytes = parseMemorySize(o.mapCache, "--map-cache");
  std::optional<ItemProgress> progress;
  if (!session.quiet) {
    progress.emplace();
    req.session.progress = progress->phases();
    req.progress = [&](const BatchProgress& p) {
      progress->line(progressLine("batch", p.done, p.total, p.job, p.phase, p.seconds, p.done, p.total - p.done));
    };
  }
  const BatchOutcome out = runBatch(req);
  if (progress) progress->finish();
  if (req.listShard) {
    for (size_t j : out.shardJobs) std::cout << req.jobs[j].name << "\t" << req.jobs[j].outputs.front().path << "\n";
    return 0;
  }
  if (!session.quiet) {
    for (const std::string& n : out.notes) std::cerr << "note: " << n << "\n";
    std::cerr << batchSummary(out);
  }
  return out.failed > 0 ? kExitJobsFailed : 0;
}

}  // namespace penumbra
