// Transmittance and collisions in one medium (core/media/tracking.h).
#include "core/media/tracking.h"
#include "core/media/density_grid.h"
#include "core/media/homogeneous.h"

namespace penumbra {

Color sigmaSAt(const Medium& m, const Vec3& p) { return m.density ? m.sigmaS * m.density->at(p) : m.sigmaS; }
Color sigmaTAt(const Medium& m, const Vec3& p) { return m.density ? m.sigmaT() * m.density->at(p) : m.sigmaT(); }
Color emissionAt(const Medium& m, const Vec3& p) {
  return m.density ? m.sigmaA * m.emission * m.density->at(p) : m.sigmaA * m.emission;
}

// TODO(media, H1): ratio tracking in grids; homogeneous closed forms only for now.
Color mediumTransmittance(const Medium& m, const Vec3&, const Vec3&, float a, float b, Rng&) {
  return transmittance(m.sigmaT(), b - a);
}

MediumCollision sampleCollision(const Medium& m, const Vec3&, const Vec3&, float a, float b, Rng& rng) {
  // Sampled by the channels' mean sigmaT; the weight corrects each channel.
  const Color st = m.sigmaT();
  const float s = (st.r + st.g + st.b) / 3.0f;
  if (!(s > 0.0f)) return {false, b, Color(1.0f)};
  const float t = a + sampleFreeFlight(s, rng.uniform());
  if (t >= b) {
    const Color tr = transmittance(st, b - a);
    return {false, b, tr / std::exp(-s * (b - a))};
  }
  const Color tr = transmittance(st, t - a);
  return {true, t, m.sigmaS * tr / (s * std::exp(-s * (t - a)))};
}

}  // namespace penumbra
