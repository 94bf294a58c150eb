// The beam radiance estimate over the volume map (gather/volume_estimate.h).
#include "gather/volume_estimate.h"
#include "core/media/density_grid.h"
#include "core/media/homogeneous.h"
#include "core/media/phase_function.h"
#include "core/media/tracking.h"

namespace penumbra {
namespace {

constexpr int kMarchSteps = 64;

// T(tMin, t) along the query: closed form, or a grid's optical depth marched once per
// gather and read back by linear interpolation for each photon.
class BeamTransmittance {
 public:
  BeamTransmittance(const Medium& m, const VolumeQuery& q, float tEnd) : sigmaT_(m.sigmaT()), t0_(q.tMin) {
    grey_ = sigmaT_.r == sigmaT_.g && sigmaT_.g == sigmaT_.b;
    if (m.homogeneous()) return;
    marched_ = true;
    step_ = std::max(tEnd - q.tMin, 0.0f) / kMarchSteps;
    depth_[0] = Color(0.0f);
    for (int i = 0; i < kMarchSteps; ++i) {
      const Vec3 mid = q.origin + (q.tMin + (i + 0.5f) * step_) * q.dir;
      depth_[i + 1] = depth_[i] + sigmaTAt(m, mid) * step_;
    }
  }
  Color operator()(float t) const {
    const float d = std::max(t - t0_, 0.0f);
    if (!marched_) return grey_ ? Color(std::exp(-std::min(sigmaT_.r * d, 1e30f))) : transmittance(sigmaT_, d);
    const float x = step_ > 0.0f ? std::min(d / step_, float(kMarchSteps)) : 0.0f;
    const int i = std::min(static_cast<int>(x), kMarchSteps - 1);
    const Color tau = depth_[i] + (depth_[i + 1] - depth_[i]) * (x - i);
    return glm::exp(-glm::min(tau, Color(1e30f)));
  }

 private:
  Color sigmaT_;
  float t0_, step_ = 0.0f;
  bool grey_ = true, marched_ = false;
  Color depth_[kMarchSteps + 1];
};

}  // namespace

VolumeEstimate volumeRadiance(const VolumePhotonMap& map, const VolumeQuery& q, const Medium& medium, int k,
                              float radius, GatherScratch&) {
  const float r = radius > 0.0f ? radius : map.radiusFor(k);
  float ta = q.tMin, tb = q.tMax;
  if (!(r > 0.0f) || !std::isfinite(r) || !(q.tMax > q.tMin) || !map.span(q.origin, q.dir, r, ta, tb)) return {};
  const BeamTransmittance tr(medium, q, tb);
  // Isotropic media skip decoding the photons' directions.
  const bool isotropic = std::abs(medium.g) < kIsotropicPhaseG;
  const float g = medium.g;
  Color sum(0.0f);
  uint32_t found = 0;
  map.beam(q.origin, q.dir, q.tMin, q.tMax, r, [&](const VolumePhoton& p, float t, float) {
    if (q.medium != kNoMedium && p.medium != q.medium) return;
    const float phase =
        isotropic ? 0.25f / kPi : henyeyGreenstein(g, -glm::dot(decodeOctahedral(p.direction), q.dir));
    sum += tr(t) * (phase * p.power.color());
    ++found;
  });
  return {sum / (kPi * r * r), found};
}

}  // namespace penumbra
