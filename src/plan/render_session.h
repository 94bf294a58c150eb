// The render session: the one wiring behind render, sweep and batch. It loads,
// plans and admits every job before any heavy work, keeps each geometry's prepared
// scene (BVH, textures) and the photon stages (LRU under a byte cap), and renders
// frames from them; the commands only choose what to render and in which order.
#pragma once
#include "core/cpu_time.h"
#include "core/progress.h"
#include <tbb/global_control.h>
#include "plan/frame_tiles.h"
#include "plan/job_admission.h"
#include "plan/map_file.h"
#include "plan/output_safety.h"
#include "plan/photon_stage.h"
#include "plan/render_budget.h"
#include "plan/render_frame.h"
#include "plan/render_plan.h"
#include "plan/reuse_key.h"
#include "plan/session_options.h"
#include "io/load_cache.h"
#include "io/scene_loader.h"
#include <functional>
#include <list>
#include <map>
#include <memory>
#include <optional>
#include <string>
#include <utility>
#include <vector>

namespace penumbra {

// One render a command asks for: a scene with its overrides, one view, and the
// files it will write (checked against each other and every input up front).
struct JobRequest {
  std::string scenePath;
  std::vector<std::string> overrides;  // the job's own, after SessionOptions::overrides
  std::string view;  // empty: the scene's render.aov
  std::vector<OutputPath> outputs;
  std::optional<std::pair<int, int>> tracePixel;
  RenderBudget budget;  // --time-limit / --target-error: passes until it is met
  // Where a progressive frame saves its finished passes on SIGTERM and resumes from
  // (plan/saved_passes.h); empty: nowhere (SIGTERM kills it).
  std::string savedPasses;
  std::optional<TileRequest> tile;  // a part of the frame (--tile, --pixel-bounds, "tiles")
};

// A job loaded, planned and admitted: nothing large is allocated yet. Its scene
// keeps the settings as the user gave them and is never rewritten; its meshes are
// the buffer every job of the same geometry shares (keys.geometry).
struct PlannedJob {
  JobRequest request;  // its overrides: the session's, then the job's own
  Scene scene;
  std::string viewName;
  Aov aov = Aov::Beauty;  // the view whose light is rendered (the beauty for the error view)
  DerivedView derived = DerivedView::None;  // writes a per-pixel figure of the beauty
  bool findEmitters = false;  // FrameOptions::findEmitters (the sweep's lighting error)
  RenderPlan plan;
  ReuseKeys keys;
  Admission admission;
  std::vector<std::string> inputs;  // every file the job reads
  std::vector<std::string> notes;   // the scene's load notes, then the plan's overrides
  double loadSeconds = 0.0;
  bool prepared = false;  // split by reach and confirmed (RenderSession::prepare)
  std::optional<PixelBounds> bounds;  // the pixels a tile renders, checked against the frame
};

// One photon budget's maps and the jobs that read them (RenderSession::photonsByBudget).
struct BudgetStage {
  PhotonStage stage;
  std::vector<const PlannedJob*> jobs;  // in the order they were given
  // What the maps cost before the first frame: their build, and for the first
  // budget also the emission they share.
  double seconds = 0.0;
  double cpuSeconds = 0.0;  // the process's CPU time over the same span
  // What a lone render of this budget spends in CPU seconds: its share of the emission
  // (the share stage.emitSeconds charges) and its maps' build.
  double emitCpuSeconds = 0.0, buildCpuSeconds = 0.0;
  uint64_t prefixOf = 0;  // > 0: cut out of an emission of this many photons
};

class RenderSession {
 public:
  explicit RenderSession(SessionOptions options);

  // Loads the scene, checks the view and the outputs, plans every pass and checks
  // the estimate without photons. Throws InputError (exit 2) before any heavy work.
  // The first job of a geometry keeps its loaded scene for the others.
  PlannedJob plan(const JobRequest& request);
  // Another view of a planned job's scene and settings, planned and admitted
  // without loading the scene again (batch's views of one job).
  PlannedJob planView(const PlannedJob& job, const std::string& view);

  // What a prepared job goes on to do: render frames, whose textures load now (a
  // builtin texture that cannot be made fails before any photon), or only emit its
  // photons or cost a plan (a maps-only prepass, a plan file), which never loads them.
  enum class PrepareFor { Frames, Photons };
  // The job's geometry built (its BVH, and its textures for frames), its light
  // split by reach, the pilot if the photons are large, and the whole estimate
  // against the memory limit: still before any photon. Needed by the steps below.
  void prepare(PlannedJob& job, PrepareFor what = PrepareFor::Frames);

  // The BVH a job's photons, pilots and plans trace: its geometry's, built once.
  const SceneAssets& geometry(const PlannedJob& job);
  // The BVH and, where its plan reads them, the textures a frame shades with (loaded
  // here if prepare did not).
  const SceneAssets& assets(const PlannedJob& job);

  // The photon maps of jobs that share them (views of one scene and settings): the
  // union of the maps they read at the largest budgets, emitted and built once and
  // kept under the byte cap for later jobs; `reused` is set when they came from it.
  // With SessionOptions::mapDir the stage's emission is loaded from its map file, or
  // emitted and written there first (plan/map_file.h); a file that does not match is
  // never used: it is emitted again and rewritten, and the stage's notes say why.
  PhotonStage& photons(const std::vector<const PlannedJob*>& jobs, bool* reused = nullptr);
  PhotonStage& photons(const PlannedJob& job, bool* reused = nullptr) { return photons({&job}, reused); }

  // The map file of the stage photons(jobs) would return, without building any map
  // (batch --maps-only): a sound file is only checked (outcome.loaded, counted in
  // mapLoads), else the photons are emitted and written (outcome.written; its note says
  // why a file there was not used); neither for jobs that emit no photons. Needs
  // SessionOptions::mapDir and prepared jobs.
  MapFileOutcome storeMaps(const std::vector<const PlannedJob*>& jobs);

  // The maps of jobs with equal keys that differ only in photon budgets (a sweep's
  // runs): one emission at each map's largest budget, then each budget's maps cut
  // from it as a prefix, the largest first; a budget that does not nest (a light
  // split that differs) is emitted alone. `visit` gets each budget on this thread.
  void photonsByBudget(const std::vector<const PlannedJob*>& jobs, const std::function<void(BudgetStage&)>& visit);

  // Every pass of one frame from `stage`, into an image (or the pixel's ray tree).
  // `clock`: the job's seconds so far, for a budget's time limit; empty: its load,
  // BVH and first photons plus the wall clock since the frame began.
  RenderResult frame(const PlannedJob& job, PhotonStage& stage, std::function<double()> clock = {},
                     std::function<void(int, const Image&, const ErrorEstimate&)> afterPass = {});

  // Files loads share are read once (io/load_cache.h); once every job is planned,
  // forgetLoads frees what the cache holds (its counts stay).
  void forgetLoads();
  // Scene and model files read from disk, each once however many jobs name it.
  size_t sceneReads() const { return sceneReads_ + loads_->sceneReads() + loads_->modelReads(); }
  size_t sceneBuilds() const { return sceneBuilds_; }
  size_t photonBuilds() const { return photonBuilds_; }
  size_t emissions() const { return emissions_; }
  size_t prefixCuts() const { return prefixCuts_; }
  size_t evictions() const { return evictions_; }
  // Photon stages read from map files, and map files written, in this process
  // (photonBuilds counts only the stages emitted here).
  size_t mapLoads() const { return mapLoads_; }
  size_t mapWrites() const { return mapWrites_; }
  uint64_t peakStageBytes() const { return peakStageBytes_; }
  const SessionOptions& options() const { return options_; }

 private:
  struct Geometry {
    Scene scene;  // the first job's load, which the BVH reads; never changed
    SceneAssets assets;
    bool textures = false;
    bool built = false;
  };
  struct CachedStage {
    PhotonStageKey key;
    std::unique_ptr<PhotonStage> stage;
  };
  Geometry& geometryOf(const PlannedJob& job);
  // The key of the stage that jobs share, and the union of the maps they read.
  PhotonStageKey stageKey(const std::vector<const PlannedJob*>& jobs, PhotonNeeds& needs) const;
  // Whether the job's stages go through map files: --map-dir, and a scene with a path
  // (one read from stdin has no key another process could match).
  bool usesMapFiles(const PlannedJob& job) const { return !options_.mapDir.empty() && job.request.scenePath != "-"; }
  // ... and the stage has photons to store (a stage without any has no file).
  bool usesMapFile(const PlannedJob& job, const PhotonNeeds& needs) const { return usesMapFiles(job) && needs.any(); }
  // The emission of `key`: from its map file where the job uses them (then `file`
  // says what happened and the counters follow), else emitted.
  // `keep` false: a sound file is only checked (storeMaps).
  Emission stageEmission(const PlannedJob& job, const PhotonStageKey& key, const PhotonNeeds& needs,
                    const std::function<Emission()>& emit, MapFileOutcome& file, bool keep = true);
  void planAndAdmit(PlannedJob& job) const;  // view, plan and estimate of a loaded job

  SessionOptions options_;  // threads resolved (> 0)
  tbb::global_control limit_;  // TBB's parallelism for the session's lifetime
  std::unique_ptr<LoadCache> loads_ = std::make_unique<LoadCache>();
  size_t sceneReads_ = 0;  // counted by caches already forgotten, and stdin's scenes
  std::map<std::string, std::unique_ptr<Geometry>> geometry_;
  std::list<CachedStage> stages_;  // most recently used first
  uint64_t peakStageBytes_ = 0;
  size_t sceneBuilds_ = 0, photonBuilds_ = 0, evictions_ = 0, emissions_ = 0, prefixCuts_ = 0;
  size_t mapLoads_ = 0, mapWrites_ = 0;
  size_t stdinJobs_ = 0;
};

}  // namespace penumbra
