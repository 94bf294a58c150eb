// A camera pilot: a coarse grid of primary rays through the real tracer, following
// mirrors and glass as the render's recursion does, to count the shading points one
// camera sample makes in this view (an orbit's frames differ: a bare wall, or glass).
#pragma once
#include "core/pixel_bounds.h"
#include "core/scene.h"
#include "geometry/trace_scene.h"

namespace penumbra {

struct CameraPilot {
  double pointsPerSample = 0.0;   // surfaces shaded per camera sample, every recursion level
  double diffusePerSample = 0.0;  // ... of those, where a path ends on a surface that is not mirror or glass
  double missesPerSample = 0.0;   // rays that leave the scene
  double texturesPerSample = 0.0; // texture lookups at those surfaces (a material may read several)
};

// Deterministic (a fixed grid over `bounds`), so every machine costs a job alike.
CameraPilot measureCamera(const Scene& scene, const TraceScene& tracer, const PixelBounds& bounds);

}  // namespace penumbra
