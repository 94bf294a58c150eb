// The batch loop: plan and admit every job, then render each through the render
// session, which shares scenes and photon stages between jobs; a job's views are
// rendered from the same maps.
#include "plan/batch/batch_run.h"
#include "plan/cpu_report.h"
#include "plan/frame_part.h"
#include "plan/image_metadata.h"
#include "plan/memory_limit.h"
#include "plan/output_safety.h"
#include "plan/render_session.h"
#include "plan/resource_estimate.h"
#include "core/error.h"
#include "io/image_io.h"
#include "io/scene_loader.h"
#include <fmt/format.h>
#include <algorithm>
#include <filesystem>
#include <map>
#include <numeric>

namespace penumbra {
namespace {

namespace fs = std::filesystem;

struct PreparedJob {
  const BatchJob* job = nullptr;
  std::vector<PlannedJob> views;  // one per output, planned and admitted
  std::vector<std::string> inputs;
  std::vector<std::string> outputs;  // each file once (views may share a layered EXR)
  std::string stamp;  // written into every output: a changed job makes them stale
  std::string frameStamp;  // a tile's: the whole frame's stamp, which its parts share
  std::string error;  // validation failure (keepGoing)
};

// The command line's budget wins over a job's own, field by field.
RenderBudget budgetOf(const BatchJob& job, const RenderBudget& command) {
  RenderBudget b = job.budget;
  if (command.seconds > 0.0) b.seconds = command.seconds;
  if (command.targetError > 0.0) b.targetError = command.targetError;
  return b;
}

// The whole frame's view files, as the job without "tiles" would have them.
std::vector<std::pair<std::string, std::string>> frameViewFiles(const BatchTile& tile) {
  std::vector<std::pair<std::string, std::string>> files;
  for (const BatchOutput& o : tile.frame) files.push_back({o.view, o.path});
  return files;
}

// A tile's part file: the merged frame gets the header the whole job's output would
// have (penumbra:job the frame's stamp); the part itself carries the tile's stamp.
void writeTile(const PreparedJob& p, size_t v, const RenderResult& result) {
  const PlannedJob& view = p.views[v];
  ImageMetadata exr = renderMetadata(view.scene, view.plan, result.stats, view.viewName, "frame.exr");
  ImageMetadata png = renderMetadata(view.scene, view.plan, result.stats, view.viewName, "frame.png");
  for (ImageMetadata* m : {&exr, &png}) m->emplace_back("penumbra:job", p.frameStamp);
  writeFramePart(p.job->outputs[v].path, result, *view.bounds, p.frameStamp, exr, png, {{"penumbra:job", p.stamp}});
}

}  // namespace

std::vector<size_t> shardJobs(const std::vector<double>& costs, size_t index, size_t count) {
  std::vector<double> load(count, 0.0);
  std::vector<size_t> mine;
  for (size_t j = 0; j < costs.size(); ++j) {
    const size_t s = static_cast<size_t>(std::min_element(load.begin(), load.end()) - load.begin());
    load[s] += costs[j];
    if (s == index) mine.push_back(j);
  }
  return mine;
}

BatchOutcome runBatch(const BatchRequest& req) {
  const CpuSpan clock;
  BatchOutcome out;
  RenderSession session(req.session);

  // 1. Every job loaded, planned and admitted, its outputs checked, before the first render.
  std::vector<PreparedJob> prepared(req.jobs.size());
  for (size_t j = 0; j < req.jobs.size(); ++j) {
    PreparedJob& p = prepared[j];
    p.job = &req.jobs[j];
    try {
      std::vector<OutputPath> outputs;
      std::vector<std::pair<std::string, std::string>> viewFiles;
      for (const BatchOutput& o : p.job->outputs) {
        viewFiles.push_back({o.view, o.path});
        if (std::find(p.outputs.begin(), p.outputs.end(), o.path) != p.outputs.end()) continue;
        p.outputs.push_back(o.path);
        outputs.push_back({o.path, "output", true});
      }
      if (p.job->outputs.empty()) throw InputError("the job writes no output");
      checkOutputs(outputs, req.extraInputs);  // the jobs file
      JobRequest first;
      first.scenePath = p.job->scene;
      first.overrides = p.job->overrides;
      first.view = p.job->outputs.front().view;
      first.outputs = outputs;
      first.budget = budgetOf(*p.job, req.session.budget);
      if (p.job->tile) first.tile = TileRequest{p.job->tile->index, p.job->tile->count, std::nullopt};
      p.views.push_back(session.plan(first));
      for (size_t v = 1; v < p.job->outputs.size(); ++v) {
        p.views.push_back(session.planView(p.views.front(), p.job->outputs[v].view));
      }
      for (const std::string& n : p.views.front().notes) {
        if (std::find(out.notes.begin(), out.notes.end(), n) == out.notes.end()) out.notes.push_back(n);
      }
      p.inputs = p.views.front().inputs;
      p.inputs.insert(p.inputs.end(), req.extraInputs.begin(), req.extraInputs.end());
      // --no-defaults changes the picture of a glTF scene: outputs of the other choice are stale.
      std::vector<std::string> stamped = p.views.front().request.overrides;  // -D, then the job's own
      if (!req.session.load.defaults) stamped.push_back("--no-defaults");
      p.stamp = jobStamp(p.job->scene, stamped, viewFiles);
      if (p.job->tile) p.frameStamp = jobStamp(p.job->scene, stamped, frameViewFiles(*p.job->tile));
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
    jobFiles.push_back({p.job->name, p.outputs, p.views.front().inputs});
  }
  checkJobsApart(jobFiles);
  // Checked as a whole, the file is cut into shards. Every shard must cut it alike, so a
  // job refused on this machine (its memory, a full disk) is costed from its scene all
  // the same; only a scene that does not load costs nothing. It is reported by its shard.
  std::vector<size_t> order(prepared.size());
  std::iota(order.begin(), order.end(), size_t(0));
  if (req.shard) {
    std::vector<double> costs;
    for (const PreparedJob& p : prepared) {
      const size_t views = p.job->outputs.size();
      if (p.error.empty()) {
        costs.push_back(shardCostNs(p.views.front().scene, views));
        continue;
      }
      try {
        costs.push_back(shardCostNs(
            loadScene(p.job->scene, jobOverrides(req.session, p.job->overrides), loadLimits(0), req.session.load), views));
      } catch (const InputError&) {
        costs.push_back(0.0);
      }
    }
    order = shardJobs(costs, req.shard->index, req.shard->count);
    out.shardJobs = order;
    if (req.listShard) return out;
  }
  // Up to date or not is decided once, before any job writes.
  std::vector<bool> current(prepared.size(), false);
  for (size_t j : order) {
    current[j] = prepared[j].error.empty() && !req.force && outputsUpToDate(prepared[j].outputs, prepared[j].stamp, prepared[j].inputs);
  }
  std::vector<bool> builtScene(prepared.size(), false);  // this job's prepare built its BVH
  // 2. The jobs to render prepared (BVH, light split, the photon estimate against the
  // memory limit) before the first photon of any of them.
  for (size_t j : order) {
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
  for (size_t j : order) {
    PreparedJob& p = prepared[j];
    BatchJobResult r;
    r.name = p.job->name;
    for (const BatchOutput& o : p.job->outputs) r.outputs.push_back(o.path);
    const CpuSpan jobClock;
    auto report = [&](const char* phase) {
      if (!req.progress) return;
      req.progress({done, order.size(), p.job->name, phase, clock.wallSeconds()});
    };
    if (!p.error.empty()) {
      r.status = "failed: " + p.error;
    } else if (current[j]) {
      r.status = "up to date";
      ++out.upToDate;
    } else {
      try {
        // The disk may have filled (or the folder gone) since the jobs were checked:
        // fail now rather than after the render.
        for (const std::string& path : p.outputs) checkImageOutputPath(path);
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
        struct Header {
          ImageMetadata meta;
          bool readsLight = false;
        };
        std::map<std::string, Header> headers;
        for (size_t v = 0; v < p.views.size(); ++v) {
          RenderResult result = session.frame(p.views[v], stage);
          if (p.job->tile) {  // one view per part file (readJobsFile)
            writeTile(p, v, result);
            continue;
          }
          // A file's header is a render's (the same keys, error and budget), from its
          // first view that reads light, else its first view; and the job's stamp.
          const std::string& path = p.job->outputs[v].path;
          const bool readsLight = result.stats.error.source != ErrorSource::None;
          auto known = headers.find(path);
          if (known == headers.end() || (readsLight && !known->second.readsLight)) {
            Header& h = headers[path];
            h.meta = renderMetadata(p.views[v].scene, p.views[v].plan, result.stats, p.views[v].viewName, path);
            h.meta.emplace_back("penumbra:job", p.stamp);
            h.readsLight = readsLight;
          }
          files[path].push_back({p.views[v].viewName, std::move(result.image)});
        }
        for (auto& [path, layers] : files) {
          ImageMetadata& meta = headers[path].meta;
          if (layers.size() == 1) {
            writeImage(path, layers.front().second, meta);
            continue;
          }
          // One header for several layers: its view is theirs, named in layer order.
          std::vector<std::string> names;
          for (const auto& layer : layers) names.push_back(layer.first);
          for (auto& [key, value] : meta)
            if (key == "penumbra:aov") value = fmt::format("{}", fmt::join(names, ","));
          writeLayeredExr(path, layers, meta);
        }
        r.status = "rendered";
        r.reused = reused.empty() ? "-" : fmt::format("{}", fmt::join(reused, "+"));
        ++out.rendered;
      } catch (const std::exception& e) {
        r.status = std::string("failed: ") + e.what();
      }
    }
    if (r.status.rfind("failed", 0) == 0) ++out.failed;
    r.cpu = jobClock.timing(session.options().threads);
    r.seconds = r.cpu.wallSeconds;
    out.jobs.push_back(r);
    ++done;
    report("done");
  }
  out.sceneBuilds = session.sceneBuilds();
  out.photonBuilds = session.photonBuilds();
  out.evictions = session.evictions();
  out.peakCacheBytes = session.peakStageBytes();
  std::vector<CpuTiming> rendered;
  for (const BatchJobResult& j : out.jobs) {
    if (j.status == "rendered") rendered.push_back(j.cpu);
  }
  const std::string contended = contendedNote(rendered, "job");
  if (!contended.empty()) out.notes.push_back(contended);
  out.cpu = clock.timing(session.options().threads);
  out.seconds = out.cpu.wallSeconds;
  return out;
}

}  // namespace penumbra
