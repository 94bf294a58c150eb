// A batch's counts as JSON (batch --stats): jobs by state, scene files read,
// scenes built, photon maps built and reused, and the shard.
#pragma once
#include "plan/batch/batch_run.h"
#include <string>

namespace penumbra {

std::string batchStatsJson(const BatchOutcome& outcome);

}  // namespace penumbra
