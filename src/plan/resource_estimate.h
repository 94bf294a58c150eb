// What a render will need before it allocates anything: photon storage, image
// buffers, BVH, lookup cache and wall time, from the scene alone (plus an optional
// pilot emission's measured store rates). Plain data; the limit check is memory_limit.h.
#pragma once
#include "core/byte_size.h"
#include "core/map_kind.h"
#include "core/scene.h"
#include "core/view.h"
#include "plan/media_estimate.h"
#include <cstdint>
#include <string>

namespace penumbra {

// Photons stored per emitted photon, for each map the render will build.
// Shadow: hits kept per shadow line; the others: stores per path (and pass).
struct StoreRates {
  PerMap<double> perPhoton;
  bool measured = false;  // true: from a pilot emission (photon_pilot.h), else analytic bounds
};

// The photons the render plan's passes emit (plan/job_admission.h: photonPlanOf).
struct PhotonPlan {
  MapCounts emitted;  // per pass
  int passes = 1;
  int photonPasses = 1;  // passes that emit their own photons (classic passes reuse pass 0's)
  uint64_t environmentPhotons = 0;  // per pass, of the global and caustic maps': those the environment starts
};

struct ResourceEstimate {
  StoreRates rates;
  PhotonPlan plan;
  double storedPhotons = 0.0;  // the largest pass's, all maps together
  // Bytes. photons: the maps as built (records + KD index); photonPeak adds the
  // transient copy made while merging and ordering them.
  double photonBytes = 0.0, photonPeakBytes = 0.0, cacheBytes = 0.0, imageBytes = 0.0,
         bvhBytes = 0.0, sceneBytes = 0.0, baseBytes = 0.0;
  double totalBytes() const {
    return photonPeakBytes + cacheBytes + imageBytes + bvhBytes + sceneBytes + baseBytes;
  }
  // Disk, not memory: the photon map file --map-dir writes (pass 0's records; 0 without).
  double mapFileBytes = 0.0;
  // What the time rests on, for the whole render (every pass): light samples drawn
  // and shadow rays cast (after the gate's share), triangles and spheres in the BVH.
  double lightSamples = 0.0, shadowRays = 0.0, primitives = 0.0;
  // Seconds of wall time on `threads` threads; renderSeconds includes bvhSeconds,
  // the acceleration structure's build.
  double photonSeconds = 0.0, renderSeconds = 0.0, bvhSeconds = 0.0;
  // A scene with a medium: what its media cost, and the parts of photonSeconds and
  // renderSeconds they take (photon flights in media; camera rays' medium work).
  MediaCost media;
  double mediaPhotonSeconds = 0.0, mediaCameraSeconds = 0.0;
  int threads = 1;
  double seconds() const { return photonSeconds + renderSeconds; }
};

struct EstimateOptions {
  PhotonPlan photons;  // the plan's photon passes
  // ... and its decisions: shadow tests, light samples, precomputed lookups.
  bool shadows = true;
  int lightSamples = 16;
  bool precomputed = false;
  Aov aov = Aov::Beauty;
  int threads = 1;
  bool tracePixel = false;  // one pixel's ray tree: no image, no passes
  bool mapFile = false;     // --map-dir: pass 0's photons are stored in a file too
  bool budgeted = false;    // --time-limit or --target-error: passes run as a progressive frame's
  // Per camera sample, from a camera pilot (plan/camera_pilot.h) where the tracer
  // exists: surfaces shaded, those of them not mirror or glass, rays that miss, and
  // texture lookups. All 0: the analytic depth factor, one gather point per sample.
  double pointsPerSample = 0.0, diffusePerSample = 0.0, missesPerSample = 0.0, texturesPerSample = 0.0;
};

// Upper bounds on stores per emitted photon from geometry and materials only.
StoreRates analyticStoreRates(const Scene& scene);

ResourceEstimate estimateResources(const Scene& scene, const EstimateOptions& options,
                                   const StoreRates& rates);

// One map of `photons` records of its kind with their KD index: what a gather searches.
double mapBytes(MapKind map, double photons);

// "~64 h": for messages (bytes: core/byte_size.h).
std::string formatDuration(double seconds);

std::string describeMemory(const ResourceEstimate& e);
// The `estimate` object of the --stats JSON.
std::string estimateToJson(const ResourceEstimate& e);

}  // namespace penumbra
