// Options of `penumbra batch`, the shard selection, the progress line and the summary.
#include "cli/batch_command.h"
#include "plan/batch/batch_jobs.h"
#include "cli/progress_line.h"
#include "plan/batch/batch_run.h"
#include "plan/batch/batch_stats.h"
#include "plan/command_support.h"
#include "plan/output_safety.h"
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
  std::string out, views, format = "png", shard, listShard, mapCache, shardIndex, shardFile, stats;
  size_t shardCount = 0, planShards = 0;
  bool keepGoing = false, status = false, mapsOnly = false, listGiven = false;
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
  c->add_option("--shard-index", o.shardIndex,
                "This task's shard, 0-based: I, or env to read SLURM_ARRAY_TASK_ID, JOB_COMPLETION_INDEX or "
                "AWS_BATCH_JOB_ARRAY_INDEX (needs --shard-count)");
  c->add_option("--shard-count", o.shardCount, "How many shards the batch is split into (with --shard-index)")
      ->check(CLI::Range(1, 100000));
  c->add_option("--shard-file", o.shardFile,
                "Take this task's jobs from a split written by --plan-shards (only those jobs' scenes are read)");
  c->add_option("--plan-shards", o.planShards, "Split the jobs into N balanced shards, write the split to -o FILE, and exit")
      ->check(CLI::Range(1, 100000));
  c->add_option("--list-shard", o.listShard,
                "Print the jobs of shard I/N (or of the shard the other options choose) with their estimated "
                "seconds, and each shard's total, and exit")
      ->expected(0, 1);
  c->add_flag("--status", o.status,
              "Render nothing: list every job as up to date, missing or stale (and why); exit 0 only when all are "
              "up to date, else " + std::to_string(kExitNotUpToDate));
  c->add_flag("--maps-only", o.mapsOnly,
              "Emit the photons of the jobs to render into --map-dir files, once per photon key, and render nothing "
              "(a farm's prepass)");
  c->add_option("--stats", o.stats, "Write the batch's counts (jobs, scenes read, maps built) as JSON to this file (- : stdout)");
  c->add_option("--map-cache", o.mapCache,
                "Photon maps kept for later jobs, at most this much (LRU), e.g. 2G (default: " +
                    formatBytes(static_cast<double>(kStageCacheBytes)) + ")");
  c->add_flag("--keep-going", o.keepGoing, "Report a job that fails validation and go on");
  addSessionOptions(*c, o.session,
                    kThreadsOption | kMaxMemoryOption | kSetOption | kQuietOption | kPlanOption | kBudgetOption |
                        kMapDirOption | kForceOption,
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
  if (!o.shardLabel.empty()) s += o.shardLabel + ": ";
  s += fmt::format("{} jobs: {} rendered, {} up to date, {} failed in {:.1f} s; {}; scene files read {}, scenes built {}, photon maps "
                   "built {} (reused {} times, {} evicted, cache peak {:.1f} MB){}\n",
                   o.jobs.size(), o.rendered, o.upToDate, o.failed, o.seconds, cpuLine(o.cpu), o.sceneReads, o.sceneBuilds,
                   o.photonBuilds, o.photonReuses, o.evictions, o.peakCacheBytes / 1e6,
                   o.mapLoads + o.mapWrites > 0
                       ? fmt::format("; map files loaded {}, written {}", o.mapLoads, o.mapWrites)
                       : "");
  return s;
}

}  // namespace

namespace {

// The shard this task renders, from --shard, --shard-index/--shard-count or neither.
std::optional<ShardChoice> shardChoice(const std::string& slash, const std::string& index, size_t count) {
  if (!slash.empty() && !index.empty()) throw InputError("--shard and --shard-index: give one of them");
  if (!index.empty() && count == 0) throw InputError("--shard-index needs --shard-count N");
  if (index.empty() && count > 0) throw InputError("--shard-count needs --shard-index (env, or a 0-based index)");
  if (!slash.empty()) return shardFromSlash(slash);
  if (!index.empty()) return shardFromIndex(index, count);
  return std::nullopt;
}

// --list-shard: the shard's jobs with their outputs and estimates, then every shard's total.
void printShardList(const BatchOutcome& out) {
  for (const BatchJobResult& j : out.jobs) {
    std::cout << j.name << "\t" << (j.outputs.empty() ? "" : j.outputs.front()) << "\t"
              << fmt::format("{:.2f} s", j.estimate) << "\n";
  }
  for (size_t s = 0; s < out.split.seconds.size(); ++s) {
    std::cout << fmt::format("# shard {}/{}: {:.2f} s estimated on one thread\n", s + 1, out.split.seconds.size(),
                             out.split.seconds[s]);
  }
}

// --status: every job's state, and the counts.
void printStatus(const BatchOutcome& out) {
  for (const BatchJobResult& j : out.jobs) {
    const std::string shard = out.shardCount ? fmt::format("shard {}/{}", j.shard + 1, out.shardCount) : "-";
    std::cout << fmt::format("{:<24} {:<12} {}\n", j.name, shard, j.status);
  }
  std::cout << fmt::format("{} jobs: {} up to date, {} missing or stale, {} failed\n", out.jobs.size(), out.upToDate,
                           out.notUpToDate, out.failed);
}

}  // namespace

int BatchCommand::run() {
  Options& o = *o_;
  BatchRequest req;
  const SessionArgs& session = o.session;
  req.session = session.options();  // contradicting options: refused before any scene is read
  const std::string gate = session.plan.gateSetting();
  const bool jobsFile = o.inputs.size() == 1 && isJobsFile(o.inputs[0]);
  o.listGiven = o.command->count("--list-shard") > 0;
  const int modes = int(o.status) + int(o.mapsOnly) + int(o.planShards > 0) + int(o.listGiven);
  if (modes > 1) throw InputError("--status, --maps-only, --plan-shards and --list-shard: give at most one");
  if (o.planShards > 0) {
    if (o.out.empty()) throw InputError("--plan-shards N writes the split to -o FILE: give -o");
    if (!jobsFile) throw InputError("--plan-shards splits a jobs file");
    if (!o.shard.empty() || !o.shardIndex.empty() || !o.shardFile.empty())
      throw InputError("--plan-shards splits every job: it takes no --shard, --shard-index or --shard-file");
  }
  if (jobsFile) {
    req.jobs = readJobsFile(o.inputs[0]);
    // The command line's gate wins over a job's own photons.gate.
    if (!gate.empty()) for (BatchJob& j : req.jobs) j.overrides.push_back(gate);
    req.protectedFiles.push_back(o.inputs[0]);
  } else {
    if (o.out.empty()) throw InputError("batch: -o DIR is required when scene files are given directly");
    req.jobs = jobsForScenes(o.inputs, o.out, o.views.empty() ? std::vector<std::string>{""} : splitValues(o.views, "--views"), "." + o.format);
  }
  req.shard = shardChoice(o.listShard.empty() ? o.shard : o.listShard, o.shardIndex, o.shardCount);
  if (!o.shardFile.empty()) {
    if (!req.shard && !o.status) {
      throw InputError("--shard-file needs the task's shard: --shard-index env --shard-count N");
    }
    req.shardFile = readShardFile(o.shardFile);
  }
  if (o.listGiven && !req.shard) throw InputError("--list-shard needs a shard: I/N, or --shard-index with --shard-count");
  req.mode = o.status ? BatchMode::Status
             : o.mapsOnly ? BatchMode::MapsOnly
             : o.planShards > 0 ? BatchMode::PlanShards
             : o.listGiven ? BatchMode::ListShard
                           : BatchMode::Render;
  req.planShards = o.planShards;
  if (o.mapsOnly && req.session.mapDir.empty()) throw InputError("--maps-only writes map files: give --map-dir DIR");
  if (req.mode == BatchMode::PlanShards) {
    checkOutputs({{o.out, "-o", false}}, req.protectedFiles);
  } else if (!jobsFile && req.mode == BatchMode::Render) {
    std::error_code ec;
    std::filesystem::create_directories(o.out, ec);
    if (ec) throw InputError(o.out + ": cannot create the output folder (" + ec.message() + ")");
  }
  req.force = session.force;
  req.keepGoing = o.keepGoing;
  if (!o.mapCache.empty()) req.session.stageCacheBytes = parseMemorySize(o.mapCache, "--map-cache");
  std::optional<ItemProgress> progress;
  const bool listing = req.mode == BatchMode::ListShard || req.mode == BatchMode::Status;
  if (!session.quiet && !listing) {
    if (req.shard) std::cerr << req.shard->label << "\n";
    progress.emplace();
    req.session.progress = progress->phases();
    req.progress = [&](const BatchProgress& p) {
      progress->line(progressLine("batch", p.done, p.total, p.job, p.phase, p.seconds, p.done, p.total - p.done));
    };
  }
  const BatchOutcome out = runBatch(req);
  if (progress) progress->finish();
  if (!o.stats.empty()) {
    if (o.stats == "-") std::cout << batchStatsJson(out);
    else writeTextOutput(o.stats, batchStatsJson(out));
  }
  switch (req.mode) {
    case BatchMode::ListShard:
      printShardList(out);
      return 0;
    case BatchMode::Status:
      printStatus(out);
      return out.upToDate == out.jobs.size() ? 0 : kExitNotUpToDate;
    case BatchMode::PlanShards: {
      ShardFile file = out.split;
      file.jobsFile = o.inputs[0];
      writeTextOutput(o.out, shardFileText(file));
      if (!session.quiet) {
        for (size_t s = 0; s < file.shards.size(); ++s) {
          std::cerr << fmt::format("shard {}/{}: {} jobs, {:.2f} s estimated on one thread\n", s + 1,
                                   file.shards.size(), file.shards[s].size(), file.seconds[s]);
        }
      }
      return 0;
    }
    default:
      break;
  }
  if (!session.quiet) {
    for (const std::string& n : out.notes) std::cerr << noteLine(n) << "\n";
    std::cerr << batchSummary(out);
  }
  return out.failed > 0 ? kExitJobsFailed : 0;
}

}  // namespace penumbra
