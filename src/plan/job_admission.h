// Whether a job may start: its resources estimated right after the scene loads
// and planned, and refused (InputError, exit 2) before anything large is allocated
// if it would not fit in memory; then, with the BVH built, measured again.
#pragma once
#include "plan/memory_limit.h"
#include "plan/render_budget.h"
#include "plan/render_plan.h"
#include "plan/resource_estimate.h"
#include "geometry/trace_scene.h"
#include <functional>
#include <string>

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
  RenderBudget budget;        // the job's --time-limit / --target-error, if any
  double budgetSeconds = 0.0;  // the longest the budget may run (budgetBoundSeconds); 0: no budget
};

// The photons the plan emits per pass, and its passes.
PhotonPlan photonPlanOf(const RenderPlan& plan, const Scene& scene, bool tracePixel);

// Step 1, before the BVH: everything but the photons against the limit (the photon
// bound may still be refined by step 2). `scene` carries the job's settings.
Admission admitJob(const Scene& scene, const RenderPlan& plan, int threads, bool tracePixel,
                   uint64_t maxMemoryBytes, const RenderBudget& budget = {});

// Step 2, with the BVH built and before any photon: the pilot if the photon bound
// is large, the whole estimate against the limit, and the long-job note.
void confirmJob(Admission& admission, const Scene& scene, const TraceScene& tracer,
                const std::function<void(const std::string&)>& notice);

// The longest a budgeted render may run: its time limit with the overrun a pass may
// add (and never under two passes), else the pass limit, at the estimate's cost per pass.
double budgetBoundSeconds(const RenderBudget& budget, const ResourceEstimate& e);

// "estimated ~64 h on 2 threads (photons 3 min, render 64 h; 1.2 GiB)"; a budgeted
// job's note gives its bound instead, with the passes and the cost of one.
std::string longJobNote(const Admission& a);

}  // namespace penumbra
