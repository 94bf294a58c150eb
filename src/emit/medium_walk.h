// A photon's flight through participating media to its next event: a collision in
// the medium it travels in, a surface, or escape, crossing invisible boundaries on the way.
#pragma once
#include "core/media/homogeneous.h"
#include "core/rng.h"
#include "core/scene.h"
#include "emit/emit.h"
#include "geometry/trace_scene.h"

namespace penumbra {

struct FlightEnd {
  enum Kind : uint8_t { Escaped, Surface, Collision, Absorbed, Lost } kind = Escaped;
  Hit hit;              // Surface: the hit
  Vec3 position{0.0f};  // Collision: where
  Color weight{1.0f};   // Collision: sigmaS T / pdf, the albedo roulette's weight
  static FlightEnd of(Kind k) {
    FlightEnd e;
    e.kind = k;
    return e;
  }
};

// Flies `ray` in medium `medium` (kNoMedium: vacuum) to its next event by free-flight
// sampling (core/media/tracking.h). Crossing an invisible boundary moves ray and medium
// on. An unscattered flight's weight (T / P(none): 1 in a grey medium) multiplies
// `power`, its change booked as absorbed; Absorbed: nothing left. Lost: caught in
// more boundary crossings than any scene needs.
FlightEnd flyToEvent(const Scene& scene, const TraceScene& tracer, Ray& ray, int& medium, Color& power, Rng& rng,
                     PhotonTally& tally);

// Russian roulette by a sampled weight: survive with q = min(1, max weight), then
// power *= weight / q, so E[power after] = power x weight per channel; the difference
// is booked as absorbed. False: the photon ends (absorbed, or a NaN or Inf power).
inline bool surviveRoulette(Color& power, const Color& weight, float u, PhotonTally& tally) {
  const float q = std::min(1.0f, maxComponent(weight));
  const Color next = u < q ? power * weight / q : Color(0.0f);
  tally.absorbed += glm::dvec3(power) - glm::dvec3(next);
  if (!(maxComponent(next) > 0.0f) || !isFinite(next)) return false;  // NaN or Inf: never stored
  power = next;
  return true;
}

// The medium a light's photons start in: the light's own, or the scene's for light
// from a direction or from infinity.
inline int startMedium(const Scene& scene, const Light& light) {
  const LightSupport support = lightTraits(light.type).support;
  return support == LightSupport::Direction || support == LightSupport::Infinite ? scene.sceneMedium : light.medium;
}

// The share of a light's photons that arrive from where they start: all of them, but
// for a light at infinity in a scene-filling homogeneous medium, which is infinite (as
// camera rays see it): only its clear channels cross. A grid's density ends at its box.
inline Color arrivingShare(const Scene& scene, const Light& light, int medium) {
  const LightSupport support = lightTraits(light.type).support;
  if (medium == kNoMedium || !(support == LightSupport::Direction || support == LightSupport::Infinite)) {
    return Color(1.0f);
  }
  const Medium& m = scene.media[static_cast<size_t>(medium)];
  if (!m.homogeneous()) return Color(1.0f);
  return transmittance(m.sigmaT(), kInf);
}

}  // namespace penumbra
