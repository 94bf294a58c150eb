// The batch loop: validate everything, then each job from cached scene assets and
// cached photon stages (LRU by bytes), its views rendered from the same maps.
#include "cli/batch_run.h"
#include "cli/output_safety.h"
#include "cli/progress_line.h"
#include "cli/render_frame.h"
#include "cli/render_plan.h"
#include "cli/reuse_key.h"
#include "core/error.h"
#include "io/image_io.h"
#include "io/scene_loader.h"
#include <tbb/global_control.h>
#include <tbb/info.h>
#include <fmt/format.h>
#include <filesystem>
#include <list>
#include <map>
#include <memory>

namespace penumbra {
namespace {

namespace fs = std::filesystem;

struct PreparedJob {
  const BatchJob* job = nullptr;
  Camera camera;  // the job's settings; its geometry lives with its group's scene
  RenderSettings render;
  PhotonSettings photons;
  ReuseKeys keys;
  std::vector<std::string> inputs;
  std::string stamp;  // written into every output: a changed job makes them stale
  std::string error;  // validation failure (keepGoing)
};

std::string stampOf(const BatchJob& job) {
  std::string s = job.scene;
  for (const std::string& o : job.overrides) s += "\n" + o;
  for (const BatchOutput& o : job.outputs) s += "\n" + o.view + ">" + o.path;
  return fmt::format("{:016x}", std::hash<std::string>{}(s));
}

// Up to date: every output exists, carries this job's stamp and is newer than every input.
bool upToDate(const PreparedJob& p, const std::vector<std::string>& extra) {
  std::error_code ec;
  for (const BatchOutput& o : p.job->outputs) {
    if (!fs::exists(o.path, ec) || readImageAttribute(o.path, "penumbra:job") != p.stamp) return false;
    const auto written = fs::last_write_time(o.path, ec);
    for (const std::string& in : p.inputs) {
      if (fs::exists(in, ec) && fs::last_write_time(in, ec) >= written) return false;
    }
    for (const std::string& in : extra) {
      if (fs::exists(in, ec) && fs::last_write_time(in, ec) >= written) return false;
    }
  }
  return true;
}

struct CachedStage {
  std::string key;
  std::unique_ptr<PhotonStage> stage;
};

}  // namespace

double jobCost(const BatchJob& job) {
  const Scene s = loadScene(job.scene, job.overrides);
  const double samples = double(s.camera.width) * s.camera.height * s.camera.spp * job.outputs.size();
  const PhotonSettings& ps = s.photons;
  // ~0.5 us per camera sample and per photon on this machine (docs/PERFORMANCE.md).
  return samples + double(ps.indirectPhotons + ps.globalPhotons + ps.causticPhotons + (ps.gate ? ps.shadowPhotons : 0));
}

BatchOutcome runBatch(const BatchRequest& req) {
  const int threads = req.threads > 0 ? req.threads : tbb::info::default_concurrency();
  tbb::global_control limit(tbb::global_control::max_allowed_parallelism, threads);
  Stopwatch clock;
  BatchOutcome out;

  // 1. Every job loaded and its outputs checked before the first render.
  std::vector<PreparedJob> prepared(req.jobs.size());
  std::map<std::string, std::unique_ptr<Scene>> owners;  // geometry key -> the scene its BVH reads
  for (size_t j = 0; j < req.jobs.size(); ++j) {
    PreparedJob& p = prepared[j];
    p.job = &req.jobs[j];
    try {
      Scene scene = loadScene(p.job->scene, p.job->overrides);
      p.keys = reuseKeys(p.job->scene, p.job->overrides);
      p.inputs = sceneInputs(scene, p.job->scene);
      std::vector<OutputPath> outputs;
      for (const BatchOutput& o : p.job->outputs) {
        parseAov(o.view.empty() ? scene.render.aov : o.view);
        bool seen = false;
        for (const OutputPath& q : outputs) seen = seen || q.path == o.path;
        if (!seen) outputs.push_back({o.path, "output", true});
      }
      checkOutputs(outputs, p.inputs);
      p.stamp = stampOf(*p.job);
      p.camera = scene.camera;
      p.render = scene.render;
      p.photons = scene.photons;
      if (!owners.count(p.keys.geometry)) owners[p.keys.geometry] = std::make_unique<Scene>(std::move(scene));
    } catch (const InputError& e) {
      p.error = e.what();
      if (!req.keepGoing) throw InputError("batch job '" + p.job->name + "' (" + p.job->where + "): " + e.what());
    }
  }

  // 2. Render, sharing what the keys allow.
  std::map<std::string, SceneAssets> assets;
  std::list<CachedStage> stages;  // most recently used first
  uint64_t cached = 0;
  size_t done = 0;
  for (PreparedJob& p : prepared) {
    BatchJobResult r;
    r.name = p.job->name;
    for (const BatchOutput& o : p.job->outputs) r.outputs.push_back(o.path);
    Stopwatch jobClock;
    auto report = [&](const std::string& phase) {
      if (!req.progress) return;
      req.progress(progressLine("batch", done, prepared.size(), p.job->name, phase, clock.seconds(), done,
                                prepared.size() - done));
    };
    if (!p.error.empty()) {
      r.status = "failed: " + p.error;
    } else if (!req.force && upToDate(p, req.extraInputs)) {
      r.status = "up to date";
      ++out.upToDate;
    } else {
      try {
        Scene& scene = *owners[p.keys.geometry];
        std::vector<std::string> reused;
        if (assets.count(p.keys.geometry)) {
          reused.push_back("scene");
        } else {
          report("scene");
          assets[p.keys.geometry] = prepareAssets(scene, true);
          ++out.sceneBuilds;
        }
        SceneAssets& a = assets[p.keys.geometry];
        // Each view's plan; the maps are built once, for the union of what they read.
        auto useSettings = [&] {
          scene.camera = p.camera;
          scene.render = p.render;
          scene.photons = p.photons;
        };
        std::vector<RenderPlan> plans;
        PhotonNeeds needs;
        PhotonSettings emitted = p.photons;
        emitted.shadowPhotons = emitted.indirectPhotons = emitted.globalPhotons = emitted.causticPhotons = 0;
        emitted.gate = false;
        bool shadows = false;
        for (const BatchOutput& o : p.job->outputs) {
          useSettings();
          plans.push_back(makePlan(scene, parseAov(o.view.empty() ? p.render.aov : o.view)));
          splitByReach(plans.back(), scene, *a.tracer);
          needs |= photonNeeds(plans.back());
          applyPlan(plans.back(), scene);
          const PhotonSettings& v = scene.photons;
          emitted.gate = emitted.gate || v.gate;
          shadows = shadows || scene.render.shadows;
          emitted.shadowPhotons = std::max(emitted.shadowPhotons, v.shadowPhotons);
          emitted.indirectPhotons = std::max(emitted.indirectPhotons, v.indirectPhotons);
          emitted.globalPhotons = std::max(emitted.globalPhotons, v.globalPhotons);
          emitted.causticPhotons = std::max(emitted.causticPhotons, v.causticPhotons);
        }
        useSettings();
        scene.photons = emitted;
        scene.render.shadows = shadows;
        const PhotonBudgets b = budgetsOf(scene);
        const std::string key = fmt::format("{}\n{}\n{} {} {} {}\n{}{}{}{}", p.keys.geometry, p.keys.photons, b.shadow,
                                            b.indirect, b.global, b.caustic, needs.shadow, needs.indirect,
                                            needs.global, needs.caustic);
        auto hit = std::find_if(stages.begin(), stages.end(), [&](const CachedStage& c) { return c.key == key; });
        if (hit != stages.end()) {
          stages.splice(stages.begin(), stages, hit);
          reused.push_back("photons");
          ++out.photonReuses;
        } else {
          report("photons");
          auto stage = std::make_unique<PhotonStage>();
          Emission e = emitPhotonsFor(scene, *a.tracer, needs, 0);
          buildStage(e, e.budgets, true, *stage);
          ++out.photonBuilds;
          cached += stage->bytes();
          stages.push_front({key, std::move(stage)});
          // Keep the newest always; drop the least recently used beyond the cap.
          while (stages.size() > 1 && cached > req.mapCacheBytes) {
            cached -= stages.back().stage->bytes();
            stages.pop_back();
            ++out.evictions;
          }
          out.peakCacheBytes = std::max(out.peakCacheBytes, cached);
        }
        PhotonStage& stage = *stages.front().stage;
        std::map<std::string, std::vector<std::pair<std::string, Image>>> files;
        for (size_t v = 0; v < plans.size(); ++v) {
          report("render " + p.job->outputs[v].view);
          useSettings();
          applyPlan(plans[v], scene);
          RenderResult result;
          FrameOptions frame;
          frame.aov = plans[v].aov;
          frame.needs = photonNeeds(plans[v]);
          renderFrame(scene, a, stage, frame, result);
          const std::string& view = p.job->outputs[v].view;
          files[p.job->outputs[v].path].push_back({view.empty() ? p.render.aov : view, std::move(result.image)});
        }
        const ImageMetadata meta = {{"penumbra:job", p.stamp}, {"penumbra:scene_file", fs::path(p.job->scene).filename().string()}};
        for (auto& [path, layers] : files) {
          if (layers.size() == 1) writeImage(path, layers.front().second, meta);
          else writeLayeredExr(path, layers, meta);
        }
        r.status = "rendered";
        r.reused = reused.empty() ? "-" : fmt::format("{}", fmt::join(reused, "+"));
        ++out.rendered;
      } catch (const std::exception& e) {
        r.status = std::string("failed: ") + e.what();
      }
    }
    if (r.status.rfind("failed", 0) == 0) ++out.failed;
    r.seconds = jobClock.seconds();
    out.jobs.push_back(r);
    ++done;
    report("done");
  }
  out.seconds = clock.seconds();
  return out;
}

std::string batchSummary(const BatchOutcome& o) {
  std::string s = fmt::format("{:<24} {:>8}  {:<14} {:<12} {}\n", "job", "time", "reused", "status", "output");
  for (const BatchJobResult& j : o.jobs) {
    const std::string status = j.status.size() > 60 ? j.status.substr(0, 57) + "..." : j.status;
    s += fmt::format("{:<24} {:>7.2f}s  {:<14} {:<12} {}\n", j.name, j.seconds, j.reused.empty() ? "-" : j.reused,
                     status, j.outputs.empty() ? "" : j.outputs.front());
  }
  s += fmt::format("{} jobs: {} rendered, {} up to date, {} failed in {:.1f} s; scenes built {}, photon maps built {} "
                   "(reused {} times, {} evicted, cache peak {:.1f} MB)\n",
                   o.jobs.size(), o.rendered, o.upToDate, o.failed, o.seconds, o.sceneBuilds, o.photonBuilds,
                   o.photonReuses, o.evictions, o.peakCacheBytes / 1e6);
  return s;
}

}  // namespace penumbra
