// The identity a frame's saved passes carry, so a resume never continues the passes
// of another picture.
#pragma once
#include "plan/render_session.h"
#include <string>

namespace penumbra {

// What a frame's saved passes must have been saved by: the scene file and the files
// it read (path, size, time: in both keys), every override, loading, the view, the
// camera and its lens, the plan, a tile's bounds and the transparent background. The
// thread count is left out: passes are seeded by index.
std::string passesIdentity(const PlannedJob& job, const SessionOptions& o);

}  // namespace penumbra
