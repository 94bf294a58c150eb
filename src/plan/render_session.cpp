// The session's steps in the order every command runs them: plan (load, view,
// outputs, plan, estimate without photons), prepare (BVH, light split, pilot,
// whole estimate), photons (cached stages), frame.
#include "plan/render_session.h"
#include "plan/transport_model.h"
#include "core/error.h"
#include "io/scene_loader.h"
#include "plan/memory_limit.h"
#include "plan/output_safety.h"
#include "plan/passes_identity.h"
#include <fmt/format.h>
#include <algorithm>
#include <filesystem>
#include <tbb/info.h>
#include <stdexcept>

namespace penumbra {

namespace {

const char* gateModeName(GateMode m) { return m == GateMode::Auto ? "auto" : m == GateMode::On ? "on" : "off"; }

// A tile's bounds in the frame, and what a tile cannot be: a budget's passes would
// differ between tiles, and the error view of one sample per pixel probes by the
// whole frame's contrast.
void checkTile(PlannedJob& job) {
  const Scene& scene = job.scene;
  const JobRequest& request = job.request;
  const char* option = request.tile->count > 0 ? "--tile" : "--pixel-bounds";
  job.bounds = resolveTile(*request.tile, scene.camera.width, scene.camera.height);
  if (request.budget.any()) {
    throw InputError(fmt::format("{}: a tile cannot run to a budget (--time-limit, --target-error): each tile would "
                                 "stop after its own passes; set photons.passes instead", option));
  }
  if (request.tracePixel) throw InputError(fmt::format("{} and --trace-pixel: give one of them", option));
  if (job.derived == DerivedView::Bias) {
    throw InputError(fmt::format("{}: the bias view averages each pixel's drift with its neighbours', which another "
                                 "tile holds; render it whole", option));
  }
  if (job.derived == DerivedView::Error && scene.camera.spp == 1 && transportOf(scene).passes(scene, job.aov) == 1) {
    throw InputError(fmt::format("{}: the error view of one sample per pixel probes by the whole frame's contrast; "
                                 "render it whole, or with --spp 2 or more", option));
  }
}

SessionOptions resolved(SessionOptions o) {
  if (o.threads <= 0) o.threads = tbb::info::default_concurrency();
  return o;
}

// --map-dir is created if missing (as -o DIR is); one that cannot be is refused before any work.
void makeMapDir(const std::string& dir) {
  if (dir.empty()) return;
  std::error_code ec;
  std::filesystem::create_directories(dir, ec);
  if (ec) throw InputError(fmt::format("--map-dir {}: cannot create it: {}", dir, ec.message()));
  if (!std::filesystem::is_directory(dir, ec)) throw InputError(fmt::format("--map-dir {}: not a directory", dir));
}

}  // namespace

RenderSession::RenderSession(SessionOptions options)
    : options_(resolved(std::move(options))),
      limit_(tbb::global_control::max_allowed_parallelism, static_cast<size_t>(options_.threads)) {
  makeMapDir(options_.mapDir);
}

PlannedJob RenderSession::plan(const JobRequest& asked) {
  PlannedJob job;
  job.request = asked;
  job.request.overrides = jobOverrides(options_, asked.overrides);
  const JobRequest& request = job.request;
  Stopwatch clock;
  LoadOptions load = options_.load;
  load.cache = loads_.get();
  if (request.scenePath == "-") ++sceneReads_;
  job.scene = loadScene(request.scenePath, request.overrides, loadLimits(options_.maxMemoryBytes), load);
  job.notes = job.scene.load.notes;
  // A tile's or a traced pixel's passes are the scene's own: a budget cannot split.
  if (!request.tile && !request.tracePixel) {
    job.request.budget = frameBudget(request.budget, job.scene.load);
    if (job.request.budget.modelDefault) job.notes.push_back(modelBudgetNote(job.scene.file));
  }
  job.loadSeconds = clock.seconds();
  if (request.scenePath == "-") {
    // A scene read from stdin can be read once: it shares nothing with another job.
    const std::string own = "-\n" + std::to_string(stdinJobs_++);
    job.keys = {own, own};
  } else {
    job.keys = reuseKeys(request.scenePath, request.overrides);
  }
  job.inputs = sceneInputs(job.scene, request.scenePath);
  if (request.scenePath != "-") {
    const std::string files = inputsStamp(job.inputs);
    job.keys.geometry += "\n" + files;
    job.keys.photons += "\n" + files;
  }
  checkOutputs(request.outputs, job.inputs);
  planAndAdmit(job);
  // Equal geometry keys mean equal meshes: every job reads the first one's buffer.
  std::unique_ptr<Geometry>& g = geometry_[job.keys.geometry];
  if (!g) {
    g = std::make_unique<Geometry>();
    g->scene = job.scene;
  }
  job.scene.meshes = g->scene.meshes;
  return job;
}

void RenderSession::forgetLoads() {
  sceneReads_ = sceneReads();
  loads_ = std::make_unique<LoadCache>();
}

PlannedJob RenderSession::planView(const PlannedJob& base, const std::string& view) {
  PlannedJob job = base;
  job.request.view = view;
  job.request.outputs.clear();  // checked with the job's first view
  job.notes.clear();
  job.prepared = false;
  planAndAdmit(job);
  return job;
}

void RenderSession::planAndAdmit(PlannedJob& job) const {
  const Scene& scene = job.scene;
  const JobRequest& request = job.request;
  job.viewName = request.view.empty() ? scene.render.aov : request.view;
  job.aov = parseAov(job.viewName);
  job.derived = derivedView(job.viewName);
  checkBudget(request.budget);
  const int passes = transportOf(scene).passes(scene, job.aov);
  if (job.derived == DerivedView::Bias && passes < kBiasMinPasses && !request.budget.any()) {
    throw InputError(fmt::format("{}: the bias view compares the first half of the passes with the second, each "
                                 "sequence in both: it needs photons.passes {} or more (the scene renders {})",
                                 scene.file, kBiasMinPasses, passes));
  }
  if (!transportOf(scene).hasView(job.aov)) {
    const char* physical = shadingModelName(ShadingModel::Physical);
    throw InputError(fmt::format("{}: view '{}' needs the {} model (render.model: \"{}\")", scene.file, job.viewName,
                                 physical, physical));
  }
  if (request.tracePixel) checkPixel(scene.camera, request.tracePixel->first, request.tracePixel->second);
  if (request.tile) checkTile(job);
  // Before any work: what runs and why (photons.gate = auto is decided here too).
  job.plan = makePlan(scene, job.aov, options_.plan);
  for (const PassDecision& d : job.plan.passes) {
    if (d.overridden && d.changesImage) job.notes.push_back("plan override: " + d.reason);
  }
  job.admission = admitJob(scene, job.plan, options_.threads, request.tracePixel.has_value(), options_.maxMemoryBytes,
                          request.budget);
  if (usesMapFiles(job)) {  // the estimate counts the file on disk
    job.admission.options.mapFile = true;
    job.admission.estimate = estimateResources(scene, job.admission.options, job.admission.bound);
  }
}

RenderSession::Geometry& RenderSession::geometryOf(const PlannedJob& job) {
  auto g = geometry_.find(job.keys.geometry);
  if (g == geometry_.end()) throw std::logic_error("a job of another session");
  return *g->second;
}

const SceneAssets& RenderSession::geometry(const PlannedJob& job) {
  Geometry& g = geometryOf(job);
  if (!g.built) {
    g.assets = prepareAssets(g.scene);
    g.built = true;
    ++sceneBuilds_;
  }
  return g.assets;
}

const SceneAssets& RenderSession::assets(const PlannedJob& job) {
  Geometry& g = geometryOf(job);
  geometry(job);
  if (job.plan[Pass::Textures].on && !g.textures) {
    g.assets.textures = loadTextures(g.scene);
    g.textures = true;
  }
  return g.assets;
}

void RenderSession::prepare(PlannedJob& job, PrepareFor what) {
  if (job.prepared) {
    // Costed for a shard first (photons only), now rendered: its textures load here.
    if (what == PrepareFor::Frames) assets(job);
    return;
  }
  const SceneAssets& a = what == PrepareFor::Frames ? assets(job) : geometry(job);
  splitByReach(job.plan, job.scene, *a.tracer);  // needs rays: the BVH is the first work
  // The split may turn a map off (nothing its lights emit can be stored): estimate what is emitted.
  Admission& admission = job.admission;
  admission.options.photons = photonPlanOf(job.plan, job.scene, job.request.tracePixel.has_value());
  admission.estimate = estimateResources(job.scene, admission.options, admission.bound);
  confirmJob(job.admission, job.scene, *a.tracer, options_.notice);
  job.prepared = true;
}

PhotonStageKey RenderSession::stageKey(const std::vector<const PlannedJob*>& jobs, PhotonNeeds& needs) const {
  const PlannedJob& job = *jobs.front();
  MapCounts budgets;
  for (const PlannedJob* j : jobs) {
    if (!j->prepared) throw std::logic_error("photons of a job not prepared");
    if (j->keys.photons != job.keys.photons) throw std::logic_error("photons shared by jobs that differ");
    needs |= photonNeeds(j->plan);
    budgets.maxWith(planBudgets(j->plan));
  }
  return {job.keys.geometry, job.keys.photons, budgets, needs.maps};
}

Emission RenderSession::stageEmission(const PlannedJob& job, const PhotonStageKey& key, const PhotonNeeds& needs,
                                 const std::function<Emission()>& emit, MapFileOutcome& file, bool keep) {
  if (!usesMapFile(job, needs)) return emit();
  beginPhase(options_.progress, "map file");
  Emission e = loadOrEmit(options_.mapDir, mapFileKey(key, needs, options_.load.defaults), emit, file, keep);
  if (file.loaded) ++mapLoads_;
  if (file.written) ++mapWrites_;
  return e;
}

PhotonStage& RenderSession::photons(const std::vector<const PlannedJob*>& jobs, bool* reused) {
  const PlannedJob& job = *jobs.front();
  PhotonNeeds needs;
  const PhotonStageKey key = stageKey(jobs, needs);
  auto hit = std::find_if(stages_.begin(), stages_.end(), [&](const CachedStage& c) { return c.key == key; });
  if (hit != stages_.end()) {
    stages_.splice(stages_.begin(), stages_, hit);
    if (reused) *reused = true;
    return *stages_.front().stage;
  }
  if (reused) *reused = false;
  const SceneAssets& a = geometry(job);
  const Scene& scene = job.scene;
  auto stage = std::make_unique<PhotonStage>();
  const PhaseGuard phases(options_.progress);
  MapFileOutcome file;
  Emission e = stageEmission(job, key, needs, [&] {
    return emitPhotonsFor(scene, *a.tracer, needs, key.budgets, 0, {}, beginPhase(options_.progress, "photons"));
  }, file);
  buildStage(e, e.budgets, true, *stage, beginPhase(options_.progress, "maps"));
  stage->buildSeconds += file.seconds;  // reading or writing the file is the maps' cost
  if (!file.note.empty()) stage->notes.push_back(file.note);
  if (!file.loaded) {
    ++emissions_;
    ++photonBuilds_;
  }
  stages_.push_front({key, std::move(stage)});
  // Counted afresh: a stage grows after it is cached (its frames add lookup caches).
  uint64_t cached = 0;
  for (const CachedStage& c : stages_) cached += c.stage->bytes();
  // Keep the newest always; drop the least recently used beyond the cap.
  while (stages_.size() > 1 && cached > options_.stageCacheBytes) {
    cached -= stages_.back().stage->bytes();
    stages_.pop_back();
    ++evictions_;
  }
  peakStageBytes_ = std::max(peakStageBytes_, cached);
  return *stages_.front().stage;
}

MapFileOutcome RenderSession::storeMaps(const std::vector<const PlannedJob*>& jobs) {
  if (options_.mapDir.empty()) throw std::logic_error("map files without --map-dir");
  const PlannedJob& job = *jobs.front();
  PhotonNeeds needs;
  const PhotonStageKey key = stageKey(jobs, needs);
  MapFileOutcome file;
  if (!usesMapFiles(job)) {
    file.note = "photon maps: a scene read from standard input has no map file";
    return file;
  }
  if (!needs.any()) return file;  // nothing to emit, nothing to store
  const PhaseGuard phases(options_.progress);
  stageEmission(job, key, needs, [&] {
    ++emissions_;
    ++photonBuilds_;
    return emitPhotonsFor(job.scene, *geometry(job).tracer, needs, key.budgets, 0, {},
                          beginPhase(options_.progress, "photons"));
  }, file, false);
  return file;
}

RenderResult RenderSession::frame(const PlannedJob& job, PhotonStage& stage, std::function<double()> clock,
                                  std::function<void(int, const Image&, const ErrorEstimate&)> afterPass) {
  if (!job.prepared) throw std::logic_error("a frame of a job not prepared");
  const SceneAssets& a = assets(job);
  const Scene& scene = job.scene;
  RenderResult result;
  result.estimate = job.admission.estimate;
  result.notes = job.notes;
  result.media = scene.hasMedia();
  RenderStats& stats = result.stats;
  stats.time.load = job.loadSeconds;
  stats.gateMode = gateModeName(scene.photons.gateMode);
  stats.gate = job.plan[Pass::Gate].on;
  stats.gateReason = job.plan[Pass::Gate].reason;
  stats.plan = planJson(job.plan);
  stats.scene = scene.name;
  stats.width = scene.camera.width;
  stats.height = scene.camera.height;
  stats.spp = scene.camera.spp;
  stats.threads = options_.threads;
  stats.seed = scene.render.seed;
  stats.model = transportOf(scene).name();
  stats.lookup = job.plan[Pass::Precompute].on ? "precomputed" : "exact";
  stats.ignoredExtensions = scene.load.ignoredExtensions;
  if (scene.load.framedCamera) stats.defaultsAdded.push_back("camera");
  if (scene.load.defaultSky) stats.defaultsAdded.push_back("sky");
  FrameOptions frame;
  frame.aov = job.aov;
  frame.needs = photonNeeds(job.plan);
  frame.budgets = planBudgets(job.plan);
  frame.choices = choicesOf(job.plan, scene);
  frame.precomputed = precomputedLookups(job.plan);
  frame.tracePixel = job.request.tracePixel;
  frame.progress = options_.progress;
  frame.budget = job.request.budget;
  if (clock) {
    frame.clock = std::move(clock);
  } else {
    // A budget counts the job's load, its BVH and its first photons (reused ones too).
    const double spent = job.loadSeconds + a.bvhSeconds + stage.emitSeconds + stage.buildSeconds;
    frame.clock = [spent, wall = Stopwatch()] { return spent + wall.seconds(); };
  }
  frame.derived = job.derived;
  frame.findEmitters = job.findEmitters;
  frame.bounds = job.bounds;
  frame.afterPass = std::move(afterPass);
  // A scene read from stdin cannot be told from another: its passes are not kept.
  if (!job.request.savedPasses.empty() && job.request.scenePath != "-") {
    frame.resume = {job.request.savedPasses, passesIdentity(job, options_), options_.force};
  }
  const PhaseGuard phases(options_.progress);
  renderFrame(scene, a, stage, frame, result);
  return result;
}

}  // namespace penumbra
