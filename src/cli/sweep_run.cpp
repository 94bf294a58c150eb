// The sweep's schedule: runs grouped by what they share (cli/reuse_key.h), the
// reference first, then each group's photon emission once, its budgets' maps
// from largest to smallest, and every run of a budget on the same maps.
#include "cli/sweep_run.h"
#include "cli/plot_script.h"
#include "cli/progress_line.h"
#include "cli/render_frame.h"
#include "cli/reuse_key.h"
#include "core/error.h"
#include "io/image_compare.h"
#include "io/image_io.h"
#include "io/scene_loader.h"
#include "io/temp_file.h"
#include <tbb/global_control.h>
#include <tbb/info.h>
#include <fmt/format.h>
#include <algorithm>
#include <filesystem>
#include <map>
#include <set>
#include <memory>

namespace penumbra {
namespace {

namespace fs = std::filesystem;

// A run, loaded and checked: its settings (the geometry lives with its group).
struct PlannedRun {
  size_t index = 0;
  Camera camera;
  RenderSettings render;
  PhotonSettings photons;
  ReuseKeys keys;
  PhotonBudgets budgets;
  RenderPlan plan;        // the run's plan (split by reach once its BVH exists)
  PhotonNeeds needs;      // ... which maps it reads
  bool textures = false;  // ... and whether it reads textures
  double loadSeconds = 0.0;
  bool done = false;  // finished by an earlier sweep into the same folder
};

// What runs of one geometry share: the scene they were loaded from and its assets.
struct GeometryGroup {
  Scene scene;  // the first run's; others swap in their camera/render/photons
  SceneAssets assets;
  bool built = false;
};

class Sweep {
 public:
  explicit Sweep(const SweepRequest& request) : req_(request), spec_(request.spec) {}

  SweepOutcome run() {
    const fs::path dir(req_.outDir);
    std::error_code ec;
    fs::create_directories(dir / "runs", ec);
    if (ec) throw InputError(req_.outDir + ": cannot create the sweep folder (" + ec.message() + ")");
    csvPath_ = (dir / "results.csv").string();
    std::map<std::string, SweepRow> finished;
    if (!req_.force) finished = readFinishedRows(csvPath_, spec_.knobs);
    plan(finished);
    loadReference();
    splitByReach();
    rows_.resize(spec_.runs.size());
    for (const PlannedRun& p : runs_) {
      if (p.done) { rows_[p.index] = finished[spec_.runs[p.index].id]; ++totals_.resumed; }
    }
    writeCsv();
    for (const std::vector<size_t>& group : photonGroups()) renderGroup(group);
    totals_.wallSeconds = clock_.seconds();
    SweepOutcome out;
    out.rows = rows_;
    out.totals = totals_;
    writeTextFileAtomic((dir / "report.md").string(), reportMarkdown(sceneName_, spec_, rows_, totals_));
    if (!req_.plotScript.empty()) plot(dir);
    out.notes = notes_;
    return out;
  }

 private:
  // Loads every run (so a bad one fails before any work) and keeps only its settings.
  void plan(const std::map<std::string, SweepRow>& finished) {
    for (size_t i = 0; i < spec_.runs.size(); ++i) {
      const SweepRun& run = spec_.runs[i];
      PlannedRun p;
      p.index = i;
      Stopwatch clock;
      Scene scene;
      try {
        scene = loadScene(req_.scenePath, run.overrides);
        p.keys = reuseKeys(req_.scenePath, run.overrides);
      } catch (const InputError& e) {
        throw InputError("sweep run '" + run.id + "': " + e.what());
      }
      p.loadSeconds = clock.seconds();
      if (i == 0) aov_ = parseAov(req_.aov.empty() ? scene.render.aov : req_.aov);
      p.plan = makePlan(scene, aov_);
      const RenderPlan& plan = p.plan;
      applyPlan(plan, scene);
      p.needs = photonNeeds(plan);
      p.textures = plan[Pass::Textures].on;
      p.camera = scene.camera;
      p.render = scene.render;
      p.photons = scene.photons;
      p.budgets = budgetsOf(scene);
      auto f = finished.find(run.id);
      p.done = f != finished.end() && fs::exists(fs::path(req_.outDir) / f->second.image);
      if (i == 0) sceneName_ = scene.name;
      if (!geometry_.count(p.keys.geometry)) {
        geometry_[p.keys.geometry] = std::make_unique<GeometryGroup>();
        geometry_[p.keys.geometry]->scene = std::move(scene);
      }
      runs_.push_back(p);
    }
  }

  void loadReference() {
    if (!req_.referencePath.empty()) {
      reference_ = readImage(req_.referencePath);
      totals_.referenceNote = "`" + req_.referencePath + "` (given with --reference)";
      return;
    }
    referenceRun_ = spec_.highest;
    totals_.referenceNote = "the run at every knob's highest value (" + spec_.runs[referenceRun_].id +
                            "), rendered by this sweep, saved as `reference.exr`";
    const fs::path saved = fs::path(req_.outDir) / "reference.exr";
    if (runs_[referenceRun_].done && fs::exists(saved)) {
      reference_ = readImage(saved.string());
    } else {
      runs_[referenceRun_].done = false;
    }
  }

  // Runs still to do, grouped by (geometry, photon key); the reference's group first.
  std::vector<std::vector<size_t>> photonGroups() const {
    std::map<std::string, std::vector<size_t>> byKey;
    std::vector<std::string> order;
    for (const PlannedRun& p : runs_) {
      if (p.done) continue;
      const std::string key = p.keys.geometry + "\n" + p.keys.photons;
      if (!byKey.count(key)) order.push_back(key);
      byKey[key].push_back(p.index);
    }
    std::vector<std::vector<size_t>> groups;
    for (const std::string& k : order) groups.push_back(byKey[k]);
    std::stable_partition(groups.begin(), groups.end(), [&](const std::vector<size_t>& g) {
      return std::find(g.begin(), g.end(), referenceRun_) != g.end();
    });
    return groups;
  }

  // Each run still to render gets the plan's light split by reach, as a lone render
  // of it would (needs its geometry's BVH, so after every run has loaded): the same
  // budgets per light, and a pass no light feeds off, in every pass of the run.
  void splitByReach() {
    for (PlannedRun& p : runs_) {
      if (p.done) continue;
      GeometryGroup& geo = assetsFor(p);
      Scene& scene = geo.scene;
      scene.camera = p.camera;
      scene.render = p.render;
      scene.photons = p.photons;
      penumbra::splitByReach(p.plan, scene, *geo.assets.tracer);
      applyPlan(p.plan, scene);
      p.render = scene.render;
      p.photons = scene.photons;
      p.budgets = budgetsOf(scene);
      p.needs = photonNeeds(p.plan);
    }
  }

  GeometryGroup& assetsFor(const PlannedRun& p) {
    GeometryGroup& g = *geometry_[p.keys.geometry];
    if (!g.built) {
      g.assets = prepareAssets(g.scene, p.textures);
      g.built = true;
      ++totals_.bvhBuilds;
      bvhSeconds_[p.keys.geometry] = g.assets.bvhSeconds;
    }
    return g;
  }

  void renderGroup(const std::vector<size_t>& group) {
    GeometryGroup& geo = assetsFor(runs_[group[0]]);
    const double bvh = bvhSeconds_[runs_[group[0]].keys.geometry];
    // One emission at each map's largest budget, gated if any run gates.
    Scene& scene = geo.scene;
    scene.camera = runs_[group[0]].camera;
    scene.render = runs_[group[0]].render;
    scene.photons = runs_[group[0]].photons;
    PhotonBudgets top;
    std::vector<uint64_t> smaller;
    std::vector<PhotonBudgets> budgets;
    PhotonNeeds needs;
    for (size_t i : group) {
      needs |= runs_[i].needs;
      const PlannedRun& p = runs_[i];
      top.maxWith(p.budgets);
      scene.photons.gate = scene.photons.gate || p.photons.gate;
      scene.render.shadows = scene.render.shadows || p.render.shadows;
      for (uint64_t b : {p.budgets.shadow, p.budgets.indirect, p.budgets.global, p.budgets.caustic}) smaller.push_back(b);
      if (std::find(budgets.begin(), budgets.end(), p.budgets) == budgets.end()) budgets.push_back(p.budgets);
    }
    top.writeTo(scene.photons);
    status_ = "photons";
    showProgress();
    Emission emission = emitPhotonsFor(scene, *geo.assets.tracer, needs, 0, smaller);
    ++totals_.emissions;
    // The reference's budget first, then the largest to the smallest.
    std::sort(budgets.begin(), budgets.end(),
              [](const PhotonBudgets& a, const PhotonBudgets& b) { return a.total() > b.total(); });
    bool emissionCharged = false;
    for (const PhotonBudgets& b : budgets) {
      PhotonStage stage;
      status_ = "maps";
      showProgress();
      Stopwatch build;
      PhotonStage* maps = &stage;
      if (!buildStage(emission, b, false, stage)) {
        // Not a prefix of this emission (a light split that does not nest): emit it alone.
        Scene alone = scene;
        b.writeTo(alone.photons);
        Emission own = emitPhotonsFor(alone, *geo.assets.tracer, needs, 0);
        ++totals_.emissions;
        buildStage(own, own.budgets, true, stage);
      } else if (stage.fromPrefix) {
        ++totals_.prefixCuts;
      }
      ++totals_.mapBuilds;
      totals_.photonSeconds += stage.emitSeconds + stage.buildSeconds;
      double firstSpent = build.seconds() + (emissionCharged ? 0.0 : emission.seconds);
      emissionCharged = true;
      std::vector<size_t> order;
      for (size_t i : group) if (runs_[i].budgets == b) order.push_back(i);
      std::stable_partition(order.begin(), order.end(), [&](size_t i) { return i == referenceRun_; });
      for (size_t i : order) {
        Reuse reuse;
        reuse.bvh = !usedGeometry_.insert(runs_[i].keys.geometry).second;
        reuse.maps = firstSpent == 0.0;
        reuse.prefixOf = stage.fromPrefix ? emission.budgets.total() : 0;
        renderRun(runs_[i], geo, *maps, bvh, firstSpent, reuse);
        firstSpent = 0.0;
      }
    }
  }

  RenderResult renderOne(GeometryGroup& geo, PhotonStage& stage, const PlannedRun& p, bool gate) {
    Scene& scene = geo.scene;
    scene.camera = p.camera;
    scene.render = p.render;
    scene.photons = p.photons;
    scene.photons.gate = gate;
    RenderResult result;
    FrameOptions frame;
    frame.aov = aov_;
    frame.needs = p.needs;
    frame.progress = [this](const char* phase, double f) {
      status_ = fmt::format("{} {:.0f}%", phase, 100.0 * f);
      showProgress();
    };
    renderFrame(scene, geo.assets, stage, frame, result);
    return result;
  }

  struct Reuse {
    bool bvh = false, maps = false;
    uint64_t prefixOf = 0;  // > 0: photons cut out of an emission of this many
  };

  void renderRun(const PlannedRun& p, GeometryGroup& geo, PhotonStage& stage, double bvh, double spentBefore,
                 const Reuse& reuse) {
    const SweepRun& run = spec_.runs[p.index];
    current_ = p.index;
    Stopwatch clock;
    RenderResult result = renderOne(geo, stage, p, p.photons.gate);
    const RenderStats& st = result.stats;
    SweepRow row;
    row.id = run.id;
    row.values = run.values;
    row.reference = p.index == referenceRun_;
    row.load = p.loadSeconds;
    row.bvh = bvh;
    row.emit = stage.emitSeconds;
    row.maps = stage.buildSeconds;
    // A lookup cache reused from an earlier run on these maps still counts in full.
    row.precompute = st.cacheRecords > 0 ? std::max(st.time.precompute, stage.lookupSeconds) : st.time.precompute;
    row.render = st.time.render;
    row.total = row.load + row.bvh + row.emit + row.maps + row.precompute + row.render;
    fillCounts(row, st);
    row.gate = p.photons.gate && st.rays.gateQueries > 0;
    std::vector<std::string> reused;
    if (reuse.bvh) reused.push_back("bvh");
    if (reuse.prefixOf > 0) reused.push_back(fmt::format("photons(prefix of {})", reuse.prefixOf));
    if (reuse.maps) reused.push_back("maps");
    for (size_t i = 0; i < reused.size(); ++i) row.reused += (i ? ";" : "") + reused[i];
    totals_.renderSeconds += row.precompute + row.render;

    if (row.reference) reference_ = result.image;
    if (row.gate && req_.compareGate) {
      status_ = "ungated";
      showProgress();
      RenderResult ungated = renderOne(geo, stage, p, false);
      row.ungatedRender = ungated.stats.time.render + ungated.stats.time.precompute;
      row.ungatedShadowRays = ungated.stats.rays.shadow;
      row.gateRmse = compareImages(result.image, ungated.image).rmse;
      totals_.renderSeconds += row.ungatedRender;
    }
    const ImageError err = compareImages(result.image, reference_);
    row.rmse = err.rmse;
    row.relMse = err.relMse;
    row.psnr = err.psnr;
    row.worstRmse = err.worstRmse;
    row.image = "runs/" + run.slug + ".exr";
    const ImageMetadata meta = {{"penumbra:sweep_run", run.id}};
    writeImage((fs::path(req_.outDir) / row.image).string(), result.image, meta);
    if (row.reference) {
      writeImage((fs::path(req_.outDir) / "reference.exr").string(), result.image, {{"penumbra:sweep_reference", run.id}});
    }
    row.spent = spentBefore + clock.seconds();
    rows_[p.index] = row;
    ++finishedNow_;
    writeCsv();
    status_ = "done";
    showProgress();
  }

  // A machine without matplotlib still gets every result, and a note saying why no plot.
  void plot(const fs::path& dir) {
    const std::string note = drawTradeoffPlot(req_.plotScript, (dir / "results.csv").string(),
                                              (dir / "tradeoff.png").string(), sceneName_);
    if (!note.empty()) notes_.push_back(note);
  }

  void writeCsv() { writeTextFileAtomic(csvPath_, resultsCsv(spec_.knobs, rows_)); }

  void showProgress() {
    if (!req_.progress) return;
    size_t todo = 0, done = 0;
    for (const PlannedRun& p : runs_) (p.done ? done : todo) += 1;
    const std::string id = current_ < spec_.runs.size() ? spec_.runs[current_].id : "";
    req_.progress(progressLine("sweep", done + finishedNow_, spec_.runs.size(), id, status_, clock_.seconds(),
                               finishedNow_, todo - finishedNow_));
  }

  const SweepRequest& req_;
  const SweepSpec& spec_;
  std::vector<PlannedRun> runs_;
  std::map<std::string, std::unique_ptr<GeometryGroup>> geometry_;
  std::map<std::string, double> bvhSeconds_;
  std::set<std::string> usedGeometry_;  // geometry keys an earlier run rendered with
  std::vector<SweepRow> rows_;
  SweepTotals totals_;
  Image reference_;
  size_t referenceRun_ = SIZE_MAX;
  size_t current_ = SIZE_MAX;
  size_t finishedNow_ = 0;
  std::string csvPath_, sceneName_, status_;
  Aov aov_ = Aov::Beauty;
  std::vector<std::string> notes_;
  Stopwatch clock_;
};

}  // namespace

SweepOutcome runSweep(const SweepRequest& request) {
  const int threads = request.threads > 0 ? request.threads : tbb::info::default_concurrency();
  tbb::global_control limit(tbb::global_control::max_allowed_parallelism, threads);
  Sweep sweep(request);
  return sweep.run();
}

}  // namespace penumbra
