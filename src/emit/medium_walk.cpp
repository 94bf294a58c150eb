// Photon flights through media (emit/medium_walk.h).
#include "emit/medium_walk.h"
#include "core/media/tracking.h"

namespace penumbra {

FlightEnd flyToEvent(const Scene& scene, const TraceScene& tracer, Ray& ray, int& medium, Color& power, Rng& rng,
                     PhotonTally& tally) {
  for (int crossing = 0; crossing < TraceScene::kMaxBoundaryCrossings; ++crossing) {
    FlightEnd e;
    const bool surface = tracer.intersect(ray, e.hit);
    TraceScene::BoundaryCrossing boundary;
    const bool crosses = tracer.nextBoundary(ray, surface ? e.hit.t : kInf, boundary);
    const float tEnd = crosses ? boundary.t : surface ? e.hit.t : kInf;
    if (medium != kNoMedium) {
      const MediumCollision c = sampleCollision(scene.media[medium], ray.origin, ray.dir, 0.0f, tEnd, rng);
      if (c.collided) {
        e.kind = FlightEnd::Collision;
        e.position = ray.origin + c.t * ray.dir;
        e.weight = c.weight;
        return e;
      }
      if (c.weight != Color(1.0f)) {
        const Color next = power * c.weight;
        tally.absorbed += glm::dvec3(power) - glm::dvec3(next);
        power = next;
        if (!(maxComponent(power) > 0.0f) || !isFinite(power)) return FlightEnd::of(FlightEnd::Absorbed);
      }
    }
    if (!crosses) {
      e.kind = surface ? FlightEnd::Surface : FlightEnd::Escaped;
      return e;
    }
    ray = Ray{spawnOrigin(boundary.surface, ray.dir), ray.dir};
    medium = boundary.beyond;
  }
  return FlightEnd::of(FlightEnd::Lost);
}

}  // namespace penumbra
