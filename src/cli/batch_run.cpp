// The batch loop: plan and admit every job, then render each through the render
// session, which shares scenes and photon stages between jobs; a job's views are
// rendered from the same maps.
#include "cli/batch_run.h"
#include "cli/progress_line.h"
#include "plan/cost_model.h"
#include "plan/output_safety.h"
#include "plan/render_session.h"
#include "core/error.h"
#include "io/image_io.h"
#include "io/scene_loader.h"
#include <fmt/format.h>
#include <filesystem>
#include <map>

namespace penumbra {
namespace {

namespace fs = std::filesystem;

struct PreparedJob {
  const BatchJob* job = nullptr;
  std::vector<PlannedJob> views;  // one per output, planned and admitted
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


}  // namespace

double jobCost(const BatchJob& job, const LoadLimits& limits) {
  const Scene s = loadScene(job.scene, job.overrides, limits);
  const double samples = double(s.camera.width) * s.camera.height * s.camera.spp * job.outputs.size();
  const PhotonSettings& ps = s.photons;
  // A camera sample and a photon cost about the same (plan/cost_model.h).
  const double photons = double(ps.indirectPhotons + ps.globalPhotons + ps.causticPhotons + (ps.gate ? ps.shadowPhotons : 0));
  return (samples + photons) * cost::kCameraSampleNs;
}

BatchOutcome runBatch(const BatchRequest& req) {
  Stopwatch clock;
  BatchOutcome out;
  RenderSession session({req.maxMemoryBytes, req.plan, req.threads, req.phases, {}, req.mapCacheBytes});

  // 1. Every job loaded, planned and admitted, its outputs checked, before the first render.
  std::vector<PreparedJob> prepared(req.jobs.size());
  for (size_t j = 0; j < req.jobs.size(); ++j) {
    PreparedJob& p = prepared[j];
    p.job = &req.jobs[j];
    try {
      std::vector<OutputPath> outputs;
      for (const BatchOutput& o : p.job->outputs) {
        bool seen = false;
        for (const OutputPath& q : outputs) seen = seen || q.path == o.path;
        if (!seen) outputs.push_back({o.path, "output", true});
      }
      if (p.job->outputs.empty()) throw InputError("the job writes no output");
      checkOutputs(outputs, req.extraInputs);  // the jobs file
      p.views.push_back(session.plan({p.job->scene, p.job->overrides, p.job->outputs.front().view, outputs, {}}));
      for (size_t v = 1; v < p.job->outputs.size(); ++v) {
        p.views.push_back(session.planView(p.views.front(), p.job->outputs[v].view));
      }
      p.inputs = p.views.front().inputs;
      p.stamp = stampOf(*p.job);
    } catch (const InputError& e) {
      p.error = e.what();
      p.views.clear();
      if (!req.keepGoing) throw InputError("batch job '" + p.job->name + "' (" + p.job->where + "): " + e.what());
    }
  }
  // No job may write what another writes or reads, whatever their order.
  std::vector<JobFiles> jobFiles;
  for (const PreparedJob& p : prepared) {
    if (!p.error.empty()) continue;
    JobFiles f{p.job->name, {}, p.inputs};
    for (const BatchOutput& o : p.job->outputs) f.outputs.push_back(o.path);
    jobFiles.push_back(std::move(f));
  }
  checkJobsApart(jobFiles);
  // Up to date or not is decided once, before any job writes.
  std::vector<bool> current(prepared.size(), false);
  for (size_t j = 0; j < prepared.size(); ++j) {
    current[j] = prepared[j].error.empty() && !req.force && upToDate(prepared[j], req.extraInputs);
  }
  std::vector<bool> builtScene(prepared.size(), false);  // this job's prepare built its BVH
  // 2. The jobs to render prepared (BVH, light split, the photon estimate against the
  // memory limit) before the first photon of any of them.
  for (size_t j = 0; j < prepared.size(); ++j) {
    PreparedJob& p = prepared[j];
    if (!p.error.empty() || current[j]) continue;
    const size_t builds = session.sceneBuilds();
    try {
      for (PlannedJob& v : p.views) session.prepare(v);
    } catch (const InputError& e) {
      p.error = e.what();
      if (!req.keepGoing) throw InputError("batch job '" + p.job->name + "' (" + p.job->where + "): " + e.what());
    } catch (const std::exception& e) {
      p.error = e.what();  // out of memory or an Embree failure: this job fails, the batch goes on
    }
    builtScene[j] = session.sceneBuilds() > builds;
  }

  // 3. Render, sharing what the keys allow.
  size_t done = 0;
  for (size_t j = 0; j < prepared.size(); ++j) {
    PreparedJob& p = prepared[j];
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
    } else if (current[j]) {
      r.status = "up to date";
      ++out.upToDate;
    } else {
      try {
        report("render");
        std::vector<std::string> reused;
        std::vector<const PlannedJob*> views;
        for (const PlannedJob& v : p.views) views.push_back(&v);
        if (!builtScene[j]) reused.push_back("scene");
        bool stageReused = false;
        PhotonStage& stage = session.photons(views, &stageReused);
        if (stageReused) {
          reused.push_back("photons");
          ++out.photonReuses;
        }
        std::map<std::string, std::vector<std::pair<std::string, Image>>> files;
        for (size_t v = 0; v < p.views.size(); ++v) {
          RenderResult result = session.frame(p.views[v], stage);
          files[p.job->outputs[v].path].push_back({p.views[v].viewName, std::move(result.image)});
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
  out.sceneBuilds = session.sceneBuilds();
  out.photonBuilds = session.photonBuilds();
  out.evictions = session.evictions();
  out.peakCacheBytes = session.peakStageBytes();
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
