// Whether a render may start: its outputs checked and its resources estimated
// right after the scene loads, and refused (InputError, exit 2) before anything
// large is allocated if it cannot write its results or would not fit in memory.
#pragma once
#include "cli/memory_limit.h"
#include "cli/pipeline.h"
#include "cli/resource_estimate.h"
#include "geometry/trace_scene.h"

namespace penumbra {

// Above this many estimated seconds the job says its estimate before it starts.
constexpr double kLongJobSeconds = 60.0;
// Above this many analytic photon bytes a pilot emission refines the store rates
// (analytic bounds for shadow lines through many surfaces are loose).
constexpr double kPilotThresholdBytes = 64.0 * 1024 * 1024;

struct Admission {
  EstimateOptions options;
  StoreRates bound;  // analytic store rates
  ResourceEstimate estimate;
  MemoryLimit limit;
};

// Step 1, before the BVH: every output path, then everything but the photons
// against the limit (the photon bound may still be refined by step 2).
Admission admitRender(const Scene& scene, const RenderRequest& request, Aov aov, int threads);

// Step 2, with the BVH built and before any photon: the pilot if the photon bound
// is large, the whole estimate against the limit, and the long-job note.
void confirmRender(Admission& admission, Scene& scene, const TraceScene& tracer,
                   const RenderRequest& request);

// "estimated ~64 h on 2 threads (photons 3 min, render 64 h; 1.2 GiB)".
std::string longJobNote(const ResourceEstimate& e);

}  // namespace penumbra
