// A batch job's estimated cost and photon key (plan/batch/job_cost.h).
#include "plan/batch/job_cost.h"
#include "core/lights/environment_map.h"
#include "plan/camera_pilot.h"
#include "plan/cost_model.h"
#include "plan/photon_pilot.h"
#include "plan/resource_estimate.h"
#include <algorithm>

namespace penumbra {
namespace {

// Whether rendering decodes an image file or samples a texture (`textures`: the
// view shades them): the image module's load, paid once by the process for all its jobs.
bool readsImages(const Scene& scene, bool textures) {
  const Light* sky = environmentOf(scene);
  return (textures && !scene.textures.empty()) || !scene.alphaMasks.empty() || (sky && sky->environment);
}

}  // namespace

JobCost jobCostOf(const std::vector<PlannedJob>& views, const TraceScene* tracer) {
  JobCost c;
  for (const PlannedJob& v : views) {
    // One thread: CPU seconds, the same on every machine whatever its cores.
    EstimateOptions o = v.admission.options;
    const bool textures = v.plan[Pass::Textures].on;
    o.threads = 1;
    // The analytic rates bound the stores per photon, loosely; a pilot measures them.
    const StoreRates rates = tracer ? measureStoreRates(v.scene, *tracer, o.photons, v.admission.bound) : v.admission.bound;
    // What this view (or tile) shows: a bare wall or glass and mirrors, in a pilot.
    if (tracer) {
      const PixelBounds bounds = v.bounds ? *v.bounds : PixelBounds::frame(v.scene.camera.width, v.scene.camera.height);
      const CameraPilot pilot = measureCamera(v.scene, *tracer, bounds);
      o.pointsPerSample = pilot.pointsPerSample;
      o.diffusePerSample = pilot.diffusePerSample;
      o.missesPerSample = pilot.missesPerSample;
      o.texturesPerSample = textures ? pilot.texturesPerSample : 0.0;
    }
    const ResourceEstimate e = estimateResources(v.scene, o, rates);
    // The BVH and the first pass's maps are paid once by the jobs that share them;
    // later progressive passes emit their own photons in every job. A tile renders
    // its share of the pixels. The process's start-up (in renderSeconds) is paid once
    // by each shard whatever its jobs, so it is left out.
    const double share = v.bounds ? double(v.bounds->pixels()) / (double(v.scene.camera.width) * v.scene.camera.height) : 1.0;
    const double stage = e.photonSeconds / std::max(1, o.photons.photonPasses);
    c.frameSeconds += std::max(0.0, e.renderSeconds - cost::kStartupSeconds - e.bvhSeconds) * share +
                      (e.photonSeconds - stage);
    c.photonSeconds = std::max(c.photonSeconds, stage + e.bvhSeconds);
    if (readsImages(v.scene, textures)) c.moduleSeconds = cost::kImageModuleSeconds;
  }
  return c;
}

PhotonStageKey photonKeyOf(const std::vector<PlannedJob>& views) {
  PhotonStageKey key;
  key.geometry = views.front().keys.geometry;
  key.photons = views.front().keys.photons;
  for (const PlannedJob& v : views) {
    key.budgets.maxWith(planBudgets(v.plan));
    const PhotonNeeds needs = photonNeeds(v.plan);
    for (MapKind k : kAllMaps) key.maps[k] = key.maps[k] || needs.maps[k];
  }
  return key;
}

}  // namespace penumbra
