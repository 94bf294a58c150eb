// The sweep's schedule: every run planned and admitted through the render session
// (one BVH per geometry), the reference first, then each photon group's emission
// once, its budgets' maps from largest to smallest, and every run of a budget on
// the same maps.
#include "plan/sweep/sweep_run.h"
#include "plan/sweep/sweep_estimate.h"
#include "plan/sweep/sweep_pictures.h"
#include "plan/sweep/sweep_folder.h"
#include "plan/sweep/sweep_idle_knobs.h"
#include "plan/sweep/sweep_reference.h"
#include "plan/sweep/sweep_report.h"
#include "plan/cpu_report.h"
#include "plan/image_metadata.h"
#include "plan/render_session.h"
#include "core/error.h"
#include "io/image_compare.h"
#include "io/image_io.h"
#include "io/temp_file.h"
#include <fmt/format.h>
#include <algorithm>
#include <filesystem>
#include <map>
#include <set>
#include <thread>

namespace penumbra {
namespace {

namespace fs = std::filesystem;

// A run of the grid: its planned job and whether an earlier sweep finished it.
struct PlannedRun {
  size_t index = 0;
  PlannedJob job;
  bool done = false;  // finished by an earlier sweep into the same folder
  bool mine = true;   // rendered by this session (a --threads list: its thread count's runs)
};

class Sweep {
 public:
  // `threads` > 0: only the runs of that value of the threads knob, on `session`
  // (which has that many workers); the other runs' rows are read back from results.csv.
  Sweep(const SweepRequest& request, RenderSession& session, int threads = 0)
      : req_(request), spec_(request.spec), session_(session), threads_(threads) {}

  SweepOutcome run() {
    if (req_.planOnly) {
      plan();
      return {};
    }
    plan();  // a bad run refuses before the folder is made
    totals_.errorOf = req_.errorOf;
    if (!req_.referencePath.empty()) {  // before the folder is made: a wrong one leaves nothing behind
      std::vector<std::pair<std::string, const PlannedJob*>> runs;
      for (const PlannedRun& p : runs_) runs.push_back({spec_.runs[p.index].id, &p.job});
      reference_ = givenReference(req_.referencePath, req_.scenePath, runs);
    }
    const fs::path dir(req_.outDir);
    std::error_code ec;
    // The names are checked in the folder they will be in; a refusal removes what it made.
    const fs::path made = fs::exists(dir, ec) ? dir / "runs" : dir;
    const bool fresh = !fs::exists(made, ec);
    fs::create_directories(dir / "runs", ec);
    if (ec) throw InputError(req_.outDir + ": cannot create the sweep folder (" + ec.message() + ")");
    try {
      checkSweepFiles(req_.outDir, spec_);
    } catch (const InputError&) {
      if (fresh) fs::remove_all(made, ec);
      throw;
    }
    csvPath_ = (dir / "results.csv").string();
    std::map<std::string, SweepRow> finished;
    const SweepIdentity identity = sweepIdentity(req_, runs_.front().job.inputs);
    if (!req_.force) {
      checkSweepFolder(req_.outDir, identity);
      finished = readFinishedRows(csvPath_, spec_.knobs);
    }
    for (PlannedRun& p : runs_) {
      auto f = finished.find(spec_.runs[p.index].id);
      // A run's image cut short (a full disk under an older penumbra) is rendered again.
      p.done = f != finished.end() && imageComplete((dir / f->second.image).string());
      p.mine = threads_ == 0 || runThreads(spec_, spec_.runs[p.index]) == threads_;
    }
    writeSweepFolder(req_.outDir, identity);
    prepare();  // the runs first: a refusal names what a lone render of the run would
    announceEstimate();
    loadReference();
    rows_.resize(spec_.runs.size());
    for (const PlannedRun& p : runs_) {
      if (p.done) {
        rows_[p.index] = finished[spec_.runs[p.index].id];
        if (p.mine) ++totals_.resumed;
      }
    }
    writeCsv();
    for (const std::vector<size_t>& group : photonGroups()) renderGroup(group);
    totals_.repeat = req_.repeat;
    totals_.emissions = session_.emissions();
    totals_.prefixCuts = session_.prefixCuts();
    totals_.mapBuilds = session_.photonBuilds();
    totals_.bvhBuilds = session_.sceneBuilds();
    totals_.cpu = clock_.timing(session_.options().threads);
    totals_.wallSeconds = totals_.cpu.wallSeconds;
    for (const std::string& n : idleKnobNotes(spec_, rows_, dir)) notes_.push_back(n);
    const std::string contended = contendedNote(renderedCpu_, "run");
    if (!contended.empty()) notes_.push_back(contended);
    SweepOutcome out;
    out.rows = rows_;
    out.totals = totals_;
    writeTextFileAtomic((dir / "report.md").string(), reportMarkdown(sceneName_, spec_, rows_, totals_, req_.metric));
    for (const std::string& n : {drawRunsSheet(dir.string(), rows_, req_.metric),
                                 req_.plotScript.empty() ? std::string()
                                                         : drawTradeoff(req_.plotScript, dir.string(), rows_,
                                                                        sceneName_, req_.metric)}) {
      if (!n.empty()) notes_.push_back(n);
    }
    out.notes = notes_;
    return out;
  }

 private:
  // Plans every run (so a bad one fails before any work).
  void plan() {
    for (size_t i = 0; i < spec_.runs.size(); ++i) {
      const SweepRun& run = spec_.runs[i];
      PlannedRun p;
      p.index = i;
      try {
        JobRequest job;
        job.scenePath = req_.scenePath;
        job.overrides = run.overrides;
        job.view = req_.aov;
        job.budget = req_.session.budget;
        p.job = session_.plan(job);
        p.job.findEmitters = req_.errorOf == ErrorFigure::Lighting;
      } catch (const InputError& e) {
        throw InputError("sweep run '" + run.id + "': " + e.what());
      }
      if (i == 0) {
        sceneName_ = p.job.scene.name;
        notes_ = p.job.scene.load.notes;  // every run loads the same files
      }
      runs_.push_back(std::move(p));
    }
  }

  void loadReference() {
    if (!req_.referencePath.empty()) {
      totals_.referenceNote = "`" + req_.referencePath + "` (given with --reference)";
      return;
    }
    const fs::path saved = fs::path(req_.outDir) / "reference.exr";
    if (req_.referencePasses > 1) {
      LongReference r = longReference(session_, req_, runs_[spec_.highest].job, saved.string(), [&] {
        status_ = "reference";
        showProgress();
      });
      estimatedDone_ += estimate_.reference;
      reference_ = std::move(r.image);
      totals_.referenceNote = std::move(r.note);
      totals_.referenceNoiseRmse = r.noiseRmse;
      return;
    }
    referenceRun_ = spec_.highest;
    totals_.referenceNote = "the run at every knob's highest value (" + spec_.runs[referenceRun_].id +
                            "), rendered by this sweep, saved as `reference.exr`";
    if (runs_[referenceRun_].done && imageComplete(saved.string())) {
      reference_ = readImage(saved.string());
    } else if (runs_[referenceRun_].done) {
      runs_[referenceRun_].done = false;
      session_.prepare(runs_[referenceRun_].job);
    }
  }

  // Runs still to do, grouped by (geometry, photon key); the reference's group first.
  std::vector<std::vector<size_t>> photonGroups() const {
    std::map<ReuseKeys, std::vector<size_t>> byKey;
    std::vector<ReuseKeys> order;
    for (const PlannedRun& p : runs_) {
      if (p.done || !p.mine) continue;
      if (!byKey.count(p.job.keys)) order.push_back(p.job.keys);
      byKey[p.job.keys].push_back(p.index);
    }
    std::vector<std::vector<size_t>> groups;
    for (const ReuseKeys& k : order) groups.push_back(byKey[k]);
    std::stable_partition(groups.begin(), groups.end(), [&](const std::vector<size_t>& g) {
      return std::find(g.begin(), g.end(), referenceRun_) != g.end();
    });
    return groups;
  }

  // What the sweep will cost, from its runs' own estimates and what they share, told
  // before the first photon; the ETA counts it down.
  void announceEstimate() {
    SweepEstimateInput in;
    in.runs.assign(spec_.runs.size(), nullptr);
    size_t todo = 0;
    for (const PlannedRun& p : runs_) {
      if (p.done || !p.mine) continue;
      in.runs[p.index] = &p.job;
      ++todo;
    }
    const PlannedRun& highest = runs_[spec_.highest];
    const std::string saved = (fs::path(req_.outDir) / "reference.exr").string();
    if (req_.referencePath.empty() && req_.referencePasses > 1 && !referenceSaved(req_, highest.job, saved)) {
      // A session of another thread count reloads what the first one rendered.
      session_.prepare(runs_[spec_.highest].job);
      in.reference = &highest.job;
      in.referencePasses = req_.referencePasses;
    }
    in.repeat = req_.repeat;
    in.compareGate = req_.compareGate;
    estimate_ = estimateSweep(in);
    const double load = loadAverage1m();
    const int cores = static_cast<int>(std::thread::hardware_concurrency());
    estimate_.stretch = busyStretch(load, cores, session_.options().threads);
    totals_.estimatedSeconds = estimate_.seconds();
    totals_.estimatedBusySeconds = estimate_.seconds() * estimate_.stretch;
    if (req_.notice && (todo > 0 || in.reference)) {
      req_.notice(describeSweepEstimate(estimate_, todo, session_.options().threads, load, cores));
    }
  }

  // Each run still to render is prepared as a lone render of it would be (its BVH,
  // the plan's light split by reach, the photon estimate against the memory limit),
  // all before the first photon.
  void prepare() {
    for (PlannedRun& p : runs_) {
      if (!p.done && p.mine) session_.prepare(p.job);
    }
  }

  // The group's budgets from the largest, the reference's run first within its own.
  void renderGroup(std::vector<size_t> group) {
    std::stable_partition(group.begin(), group.end(), [&](size_t i) { return i == referenceRun_; });
    std::vector<const PlannedJob*> jobs;
    for (size_t i : group) jobs.push_back(&runs_[i].job);
    const SceneAssets& assets = session_.geometry(*jobs.front());
    status_ = "photons";
    showProgress();
    session_.photonsByBudget(jobs, [&](BudgetStage& b) {
      totals_.photonSeconds += b.stage.emitSeconds + b.stage.buildSeconds;
      double spent = b.seconds, spentCpu = b.cpuSeconds;
      for (const PlannedJob* j : b.jobs) {
        const PlannedRun& run = *std::find_if(runs_.begin(), runs_.end(), [&](const PlannedRun& r) { return &r.job == j; });
        Reuse reuse;
        reuse.bvh = !usedGeometry_.insert(run.job.keys.geometry).second;
        reuse.maps = j != b.jobs.front();
        reuse.prefixOf = b.prefixOf;
        renderRun(run, b, assets, spent, spentCpu, reuse);
        spent = spentCpu = 0.0;
      }
    });
  }

  // The run's frame, or with gate = false the same run with every shadow ray cast.
  RenderResult renderOne(PhotonStage& stage, const PlannedRun& p, bool gate) {
    if (gate) return session_.frame(p.job, stage);
    PlannedJob ungated = p.job;
    ungated.plan[Pass::Gate].on = false;
    return session_.frame(ungated, stage);
  }

  struct Reuse {
    bool bvh = false, maps = false;
    uint64_t prefixOf = 0;  // > 0: photons cut out of an emission of this many
  };

  // `spentBefore` and `cpuBefore`: what the run's shared photon stage cost first.
  // The row's times are a lone render's: every stage in full, the shared ones too, and
  // each progressive pass's own emission and maps as the frame timed them.
  void renderRun(const PlannedRun& p, BudgetStage& b, const SceneAssets& bvh, double spentBefore, double cpuBefore,
                 const Reuse& reuse) {
    PhotonStage& stage = b.stage;
    const SweepRun& run = spec_.runs[p.index];
    current_ = p.index;
    const CpuSpan clock;
    RenderResult result = renderOne(stage, p, true);
    // The emitter mask a lone render of a run without a spread would not trace is not its cost.
    const double frameWall = clock.wallSeconds();
    const double frameCpu = std::max(0.0, clock.cpuSeconds() * (1.0 - result.emitterSeconds / std::max(frameWall, 1e-9)));
    const RenderStats& st = result.stats;
    SweepRow row;
    row.id = run.id;
    row.values = run.values;
    row.reference = p.index == referenceRun_;
    row.load = p.job.loadSeconds;
    row.bvh = bvh.bvhSeconds;
    // Pass 0's share of the group's emission and its maps, then every later pass's own.
    row.emit = st.time.emit;
    row.maps = st.time.buildMaps;
    // A lookup cache reused from an earlier run on these maps still counts in full.
    row.precompute = st.cacheRecords > 0 ? std::max(st.time.precompute, stage.lookupSeconds) : st.time.precompute;
    // --repeat: the same frame again on the same maps (same pixels); the fastest counts.
    std::vector<double> renders = {st.time.render};
    for (int k = 1; k < req_.repeat; ++k) renders.push_back(renderOne(stage, p, true).stats.time.render);
    setRenderTimes(row, std::move(renders));
    row.total = row.load + row.bvh + row.emit + row.maps + row.precompute + row.render;
    // The same account in CPU seconds. Loading is serial (its wall is its CPU); a lookup
    // cache reused from an earlier run is charged at this frame's CPU per wall second.
    const double reusedLookup = row.precompute - st.time.precompute;
    row.totalCpu = row.load + bvh.bvhCpuSeconds + b.emitCpuSeconds + b.buildCpuSeconds + frameCpu +
                   (frameWall > 0.0 ? reusedLookup * frameCpu / frameWall : 0.0);
    fillCounts(row, st);
    row.gate = p.job.plan[Pass::Gate].on && st.rays.gateQueries > 0;
    row.reused = reusedList(reuse.bvh, reuse.prefixOf, reuse.maps);
    totals_.renderSeconds += row.precompute + row.render;

    if (row.reference) reference_ = result.image;
    if (row.gate && req_.compareGate) {
      status_ = "ungated";
      showProgress();
      RenderResult ungated = renderOne(stage, p, false);
      row.ungatedRender = ungated.stats.time.render + ungated.stats.time.precompute;
      row.ungatedShadowRays = ungated.stats.rays.shadow;
      row.gateRmse = compareImages(result.image, ungated.image).rmse;
      totals_.renderSeconds += row.ungatedRender;
    }
    const ImageError err = compareImages(result.image, reference_, result.emitters);
    totals_.emitterShare = std::max(totals_.emitterShare, err.leftOutShare);
    fillErrors(row, err, st.error, req_.errorOf);
    row.image = "runs/" + run.slug + ".exr";
    // A run's image says what a render's would, and which run it is.
    const std::string runPath = (fs::path(req_.outDir) / row.image).string();
    ImageMetadata meta = renderMetadata(p.job.scene, p.job.plan, st, p.job.viewName, runPath);
    meta.emplace_back("penumbra:sweep_run", run.id);
    writeImage(runPath, result.image, meta);
    if (row.reference) {
      meta.back() = {"penumbra:sweep_reference", run.id};
      writeImage((fs::path(req_.outDir) / "reference.exr").string(), result.image, meta);
    }
    const CpuTiming cpu = clock.timing(session_.options().threads, spentBefore, cpuBefore);
    row.spent = cpu.wallSeconds;
    row.cpu = cpu.cpuSeconds;
    row.cpuShare = cpu.share;
    row.loadAverage = cpu.loadAverage;
    renderedCpu_.push_back(cpu);
    rows_[p.index] = row;
    ++finishedNow_;
    estimatedDone_ += estimate_.runs[p.index];
    writeCsv();
    status_ = "done";
    showProgress();
  }

  void writeCsv() { writeTextFileAtomic(csvPath_, resultsCsv(spec_.knobs, rows_)); }

  void showProgress() {
    if (!req_.progress) return;
    size_t todo = 0, done = 0;
    for (const PlannedRun& p : runs_) {
      if (p.mine) (p.done ? done : todo) += 1;
    }
    SweepProgress p;
    p.done = done + finishedNow_;
    p.total = done + todo;
    p.run = current_ < spec_.runs.size() ? spec_.runs[current_].id : "";
    p.phase = status_;
    p.seconds = clock_.wallSeconds();
    p.paced = finishedNow_;
    p.remaining = todo - finishedNow_;
    p.pacedSeconds = estimatedDone_;
    p.remainingSeconds = p.remaining == 0 ? 0.0 : std::max(0.0, estimate_.seconds() - estimatedDone_);
    req_.progress(p);
  }

  const SweepRequest& req_;
  const SweepSpec& spec_;
  RenderSession& session_;
  std::vector<PlannedRun> runs_;
  std::set<std::string> usedGeometry_;  // geometry keys an earlier run rendered with
  std::vector<SweepRow> rows_;
  SweepTotals totals_;
  Image reference_;
  size_t referenceRun_ = SIZE_MAX;
  size_t current_ = SIZE_MAX;
  size_t finishedNow_ = 0;
  const int threads_;
  std::string csvPath_, sceneName_, status_;
  std::vector<std::string> notes_;
  std::vector<CpuTiming> renderedCpu_;  // the runs rendered now (not resumed)
  SweepEstimate estimate_;
  double estimatedDone_ = 0.0;  // the estimate's seconds of the work finished so far
  CpuSpan clock_;
};

}  // namespace

SweepOutcome runSweepSession(const SweepRequest& request, int threads, bool onlyThatCount) {
  SessionOptions options = request.session;
  options.threads = threads;
  RenderSession session(options);
  return Sweep(request, session, onlyThatCount ? threads : 0).run();
}

}  // namespace penumbra
