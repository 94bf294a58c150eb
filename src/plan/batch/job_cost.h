// What a planned batch job costs a shard, from the estimate a render prints, and
// the photon key that decides which jobs share its maps.
#pragma once
#include "plan/batch/shard_split.h"
#include "plan/photon_stage.h"
#include "plan/render_session.h"
#include <vector>

namespace penumbra {

// Seconds on one thread: the views' frames (every pass, the gate and lookups as
// planned), the maps they share (with the BVH they need), charged once, and the image
// module where they read images, charged once per shard. With the views' BVH, the photons stored
// per emitted one come from a pilot emission and the shading points per sample
// from a camera pilot (deterministic, so every machine costs alike), else from the
// analytic bounds.
JobCost jobCostOf(const std::vector<PlannedJob>& views, const TraceScene* tracer);

// The key of the photon stage the views share (RenderSession::photons' key).
PhotonStageKey photonKeyOf(const std::vector<PlannedJob>& views);

}  // namespace penumbra
