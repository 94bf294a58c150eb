// Options of `penumbra sweep`, the progress line, and the closing summary.
#include "cli/sweep_command.h"
#include "plan/sweep/sweep_run.h"
#include "plan/sweep/sweep_scenes.h"
#include "plan/command_support.h"
#include "cli/session_args.h"
#include "cli/progress_line.h"
#include "cli/progress_meter.h"
#include "plan/cpu_report.h"
#include "plan/memory_limit.h"
#include "core/error.h"
#include <fmt/format.h>
#include <unistd.h>
#include <filesystem>
#include <optional>
#include <iostream>

namespace penumbra {

struct SweepCommand::Options {
  CLI::App* command = nullptr;
  std::vector<std::string> scenes;
  std::string out, reference, aov, photons, k, depth, spp;
  std::vector<std::string> vary;
  SessionArgs session;  // its budget is every run's
  int repeat = 1, referencePasses = 8;
  std::string metric = "relmse";
  ErrorFigure errorOf = ErrorFigure::Lighting;
  bool force = false, noGateCompare = false;
};

SweepCommand::SweepCommand(CLI::App& app) : o_(std::make_unique<Options>()) {
  Options& o = *o_;
  o.command = app.add_subcommand("sweep", "Render every combination of settings and measure time against error");
  CLI::App* c = o.command;
  c->add_option("scenes", o.scenes, "Scene files (JSON); with several, each is swept into OUTPUT/<its name>/ and "
                "OUTPUT/scenes.md sums them up")->required();
  c->add_option("-o,--output", o.out, "Folder for results.csv, report.md, tradeoff.png and the images")->required();
  c->add_option("--photons", o.photons, "Photon budgets, e.g. 1e4,1e5,1e6 (classic: photons.indirect; physical: photons.global and photons.caustic, and photons.volume with a medium)");
  c->add_option("--k", o.k, "Photons per estimate, e.g. 10,50,200 (classic: k_indirect; physical: k_global and k_caustic, and k_volume with a medium)");
  c->add_option("--depth", o.depth, "render.max_depth values, e.g. 1,2,4,8");
  c->add_option("--spp", o.spp, "camera.spp values, e.g. 1,4");
  c->add_option("--vary", o.vary, "Any scene key and its values: --vary photons.shadow=1e5,1e6 (repeatable)");
  c->add_option("--reference", o.reference, "Reference image (EXR) for the error (default: the sweep renders its own, see --reference-passes)");
  c->add_option("--reference-passes", o.referencePasses, "Without --reference: the reference is the run at every knob's highest value "
                "with N times its progressive passes (default 8); 1 = that run itself")->check(CLI::Range(1, 4096));
  c->add_option("--metric", o.metric, "What the front, the plot and the best run rank by: relmse (default), rmse, psnr or rmse-clamped; results.csv keeps every one");
  c->add_option_function<std::string>(
       "--error-of", [&o](const std::string& name) { o.errorOf = parseErrorFigure(name); },
       "The pixels every error column is over: lighting (default: those that see no emitter directly) or image")
      ->check(CLI::IsMember(std::vector<std::string>(kErrorFigureNames.begin(), kErrorFigureNames.end())));
  c->add_option("--aov", o.aov, "View to render (default: the scene's render.aov)");
  c->add_flag("--force", o.force, "Render every run again, even those results.csv already has");
  c->add_flag("--no-gate-compare", o.noGateCompare, "Skip the ungated render of each gated run");
  addSessionOptions(*c, o.session,
                    kThreadsOption | kMaxMemoryOption | kSetOption | kQuietOption | kPlanOption | kBudgetOption |
                        kMapDirOption,
                    "run",
                    "Worker threads (default: all cores); a list, e.g. 1,2, is a knob: every run at each count, each "
                    "count in its own session");
  c->add_option("--repeat", o.repeat, "Render each run's frame N times on its maps; keep the fastest and the median "
                "(render_s, render_median_s)")->check(CLI::Range(1, 1000));
}

SweepCommand::~SweepCommand() = default;

bool SweepCommand::selected() const { return o_->command->parsed(); }

int SweepCommand::run() {
  Options& o = *o_;
  const SessionArgs& session = o.session;
  SessionOptions options = session.options();  // contradicting options: refused before the scene is read
  const SweepMetric metric = parseMetric(o.metric);  // before the scene is read
  const SweepKnob threadList = session.threads.empty() ? SweepKnob{} : threadsKnob(session.threads);
  options.threads = threadList.values.size() == 1 ? std::atoi(threadList.values.front().c_str()) : 0;
  if (o.scenes.size() > 1 && !o.reference.empty()) {
    throw InputError("sweep: --reference is one image, for one scene; several scenes take their own references");
  }
  const std::vector<std::string> folders = sceneFolders(o.scenes, o.out);

  const std::filesystem::path script = std::filesystem::path(PENUMBRA_SOURCE_DIR) / "scripts" / "plot_tradeoff.py";
  const std::string plotScript = std::filesystem::exists(script) ? script.string() : "";
  std::vector<SweepRequest> requests;
  for (size_t i = 0; i < o.scenes.size(); ++i) {
    // The knobs' keys depend on the model: load the scene once with the sweep's --set.
    const Scene base = loadJobScene(o.scenes[i], options);
    std::vector<SweepKnob> knobs;
    const std::pair<const char*, const std::string*> named[] = {
        {"photons", &o.photons}, {"k", &o.k}, {"depth", &o.depth}, {"spp", &o.spp}};
    for (const auto& [name, list] : named) {
      if (!list->empty()) knobs.push_back(namedKnob(name, *list, transportOf(base), base.hasMedia()));
    }
    for (const std::string& v : o.vary) knobs.push_back(keyKnob(v));
    if (threadList.values.size() > 1) knobs.push_back(threadList);

    SweepRequest req;
    req.session = options;  // its -D and --gate come before each run's knobs
    req.scenePath = o.scenes[i];
    req.outDir = folders[i];
    req.spec = expandGrid(knobs, {});
    req.referencePath = o.reference;
    req.referencePasses = o.referencePasses;
    req.metric = metric;
    req.errorOf = o.errorOf;
    req.aov = o.aov;
    req.force = o.force;
    req.compareGate = !o.noGateCompare;
    req.repeat = o.repeat;
    req.plotScript = plotScript;
    requests.push_back(std::move(req));
  }
  // Every scene's every run is loaded and planned before the first renders.
  if (requests.size() > 1) {
    for (SweepRequest req : requests) {
      req.planOnly = true;
      runSweep(req);
    }
  }
  std::vector<SceneSweep> done;
  for (SweepRequest& req : requests) {
    std::optional<ItemProgress> progress;
    if (!session.quiet) {
      progress.emplace();
      req.session.progress = progress->phases();
      req.progress = [&](const SweepProgress& p) {
        // Runs differ in cost (the reference most): the ETA extrapolates estimated seconds where known.
        const bool estimated = p.pacedSeconds + p.remainingSeconds > 0.0;
        progress->line(progressLine("sweep", p.done, p.total, p.run, p.phase, p.seconds,
                                    estimated ? p.pacedSeconds : double(p.paced),
                                    estimated ? p.remainingSeconds : double(p.remaining)));
      };
      req.notice = [](const std::string& note) { std::cerr << noteLine(note) << "\n"; };
    }
    SweepOutcome out = runSweep(req);
    if (progress) progress->finish();
    if (!session.quiet) {
      for (const std::string& n : out.notes) std::cerr << noteLine(n) << "\n";
      const SweepTotals& t = out.totals;
      std::cerr << fmt::format("sweep: {} runs ({} resumed) in {:.1f} s; {}; {} emission(s), {} prefix cut(s), {} map "
                               "build(s), {} BVH build(s)\n",
                               out.rows.size(), t.resumed, t.wallSeconds, cpuLine(t.cpu), t.emissions, t.prefixCuts,
                               t.mapBuilds, t.bvhBuilds);
      std::cerr << "wrote " << (std::filesystem::path(req.outDir) / "report.md").string() << "\n";
    }
    done.push_back({req.scenePath, req.outDir, std::move(out)});
  }
  if (requests.size() > 1) {
    const std::string summary = (std::filesystem::path(o.out) / "scenes.md").string();
    writeTextOutput(summary, scenesMarkdown(done, metric));
    if (!session.quiet) std::cerr << "wrote " << summary << "\n";
  }
  return 0;
}

}  // namespace penumbra
