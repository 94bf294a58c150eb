// A ray's stretches between invisible medium boundaries: the medium changes there and
// only there (surfaces end a stretch where the caller stops the walk).
#pragma once
#include "geometry/trace_scene.h"
#include <algorithm>

namespace penumbra {

// Calls f(medium, from, to) for each stretch of [ray.tMin, tEnd] (ray.dir unit), in
// order, starting in `medium`; stops early when f returns false. Returns the medium at
// tEnd. After a boundary the next query starts past the boundary's rounding
// (spawnOrigin) and is measured on the ray's own parameter, so stretches add up to its
// length. Without boundaries: one call, no query.
template <class F>
int walkStretches(const TraceScene& tracer, const Ray& ray, float tEnd, int medium, F&& f) {
  float from = ray.tMin;
  if (!tracer.hasBoundaries()) {
    if (tEnd > from) f(medium, from, tEnd);
    return medium;
  }
  Ray probe = ray;
  for (int crossing = 0; crossing <= TraceScene::kMaxBoundaryCrossings; ++crossing) {
    const float shift = glm::dot(probe.origin - ray.origin, ray.dir);
    TraceScene::BoundaryCrossing c;
    const bool more = crossing < TraceScene::kMaxBoundaryCrossings && tracer.nextBoundary(probe, tEnd - shift, c);
    const float to = more ? std::min(tEnd, shift + c.t) : tEnd;
    if (to > from && !f(medium, from, to)) return medium;
    if (!more || to >= tEnd) return medium;
    medium = c.beyond;
    from = to;
    probe = Ray{spawnOrigin(c.surface, ray.dir), ray.dir};
  }
  return medium;
}

}  // namespace penumbra
