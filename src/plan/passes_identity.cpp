// The identity a frame's saved passes carry (plan/passes_identity.h).
#include "plan/passes_identity.h"
#include "core/adaptive_sampling.h"

#include <fmt/format.h>

namespace penumbra {

std::string passesIdentity(const PlannedJob& job, const SessionOptions& o) {
  const Camera& c = job.scene.camera;
  auto vec = [](const Vec3& v) { return fmt::format("{} {} {}", v.x, v.y, v.z); };
  return fmt::format("scene {}\noverrides {}\ndefaults {}\nview {} error {}\ncamera {} / {} / {} fov {} ortho {} "
                     "{}x{} spp {} lens {} {} {}\nseed {}\nplan {}\ngeometry {}\nphotons {}\nbounds {}\n"
                     "transparent {}\nadaptive {} {} {}",
                     job.request.scenePath, fmt::join(job.request.overrides, " "), o.load.defaults, job.viewName,
                     static_cast<int>(job.derived), vec(c.position), vec(c.lookAt), vec(c.up), c.fovY, c.orthoHeight, c.width,
                     c.height, c.spp, c.apertureRadius, c.fNumber, c.focusDistance, job.scene.render.seed,
                     planJson(job.plan), job.keys.geometry, job.keys.photons,
                     job.bounds ? fmt::format("{},{},{},{}", job.bounds->x0, job.bounds->x1, job.bounds->y0,
                                              job.bounds->y1)
                                : std::string("frame"),
                     job.scene.render.transparentBackground, adaptiveSampling(job.scene.render),
                     job.scene.render.adaptiveThreshold, job.scene.render.adaptiveMaxSpp);
}

}  // namespace penumbra
