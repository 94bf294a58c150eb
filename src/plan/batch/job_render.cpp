// A batch job's views rendered and written (plan/batch/job_render.h).
#include "plan/batch/job_render.h"
#include "plan/frame_part.h"
#include "plan/image_metadata.h"
#include "plan/saved_passes.h"
#include "io/image_io.h"
#include <fmt/format.h>
#include <map>

namespace penumbra {

namespace {

// A tile's part file: the merged frame gets the header the whole job's output would
// have (penumbra:job the frame's stamp); the part itself carries the tile's stamp
// and inputs, which decide whether it is up to date.
void writeTile(const std::string& path, const PlannedJob& view, const RenderResult& result, const JobStamps& stamps) {
  ImageMetadata exr = renderMetadata(view.scene, view.plan, result.stats, view.viewName, "frame.exr");
  ImageMetadata png = renderMetadata(view.scene, view.plan, result.stats, view.viewName, "frame.png");
  for (ImageMetadata* m : {&exr, &png}) {
    m->emplace_back(kJobStampAttribute, stamps.frame);
    m->emplace_back(kJobInputsAttribute, inputsAttribute(stamps.inputs));
  }
  writeFramePart(path, result, *view.bounds, stamps.frame, exr, png,
                 {{kJobStampAttribute, stamps.job}, {kJobInputsAttribute, inputsAttribute(stamps.inputs)}});
}

}  // namespace

JobRender renderJob(RenderSession& session, const BatchJob& job, const std::vector<PlannedJob>& views,
                    const JobStamps& stamps) {
  JobRender r;
  std::vector<const PlannedJob*> shared;
  for (const PlannedJob& v : views) shared.push_back(&v);
  PhotonStage& stage = session.photons(shared, &r.photonsReused);
  std::map<std::string, std::vector<std::pair<std::string, Image>>> files;
  struct Header {
    ImageMetadata meta;
    bool readsLight = false;
  };
  std::map<std::string, Header> headers;
  for (size_t v = 0; v < views.size(); ++v) {
    RenderResult result = session.frame(views[v], stage);
    for (const std::string& n : result.notes) {
      if (n.rfind(views[v].request.savedPasses + ": ", 0) == 0) r.notes.push_back(n);
    }
    const std::string& path = job.outputs[v].path;
    if (job.tile) {
      writeTile(path, views[v], result, stamps);
      continue;
    }
    // A file's header is a render's (the same keys, error and budget), from its
    // first view that reads light, else its first view; and the job's stamp and inputs.
    const bool readsLight = result.stats.error.source != ErrorSource::None;
    auto known = headers.find(path);
    if (known == headers.end() || (readsLight && !known->second.readsLight)) {
      Header& h = headers[path];
      h.meta = renderMetadata(views[v].scene, views[v].plan, result.stats, views[v].viewName, path);
      h.meta.emplace_back(kJobStampAttribute, stamps.job);
      h.meta.emplace_back(kJobInputsAttribute, inputsAttribute(stamps.inputs));
      h.readsLight = readsLight;
    }
    files[path].push_back({views[v].viewName, std::move(result.image)});
  }
  for (auto& [path, layers] : files) {
    ImageMetadata& meta = headers[path].meta;
    if (layers.size() == 1) {
      writeImage(path, layers.front().second, meta, sceneDisplay({}, views.front().scene));  // a model's curve
      continue;
    }
    // One header for several layers: its view is theirs, named in layer order.
    std::vector<std::string> names;
    for (const auto& layer : layers) names.push_back(layer.first);
    for (auto& [key, value] : meta)
      if (key == "penumbra:aov") value = fmt::format("{}", fmt::join(names, ","));
    writeLayeredExr(path, layers, meta);
  }
  for (const PlannedJob& v : views) removeSavedPasses(v.request.savedPasses);
  return r;
}

}  // namespace penumbra
