// Cone-filtered indirect estimators; everything finite for any input.
#include "gather/indirect_estimate.h"
#include <algorithm>
#include <cmath>
#include <limits>

namespace penumbra {

namespace {
// Keeps the photons passing the normal filter (in order) and returns the cone-weighted
// power sum over them; fills found and dMax.
Color coneSum(const IndirectPhoton* photons, GatherScratch& s, size_t count, const Vec3& n,
              float minNormalCos, IndirectEstimate& e) {
  size_t kept = 0;
  float far2 = 0.0f;  // the photons come in any order: track the farthest kept one
  const NormalFilter filter(n, minNormalCos);
  for (size_t i = 0; i < count; ++i) {
    if (!filter.passes(photons[s.indices[i]].normal)) continue;
    s.indices[kept] = s.indices[i];
    s.dist2[kept] = s.dist2[i];
    far2 = std::max(far2, s.dist2[i]);
    ++kept;
  }
  e.found = static_cast<int>(kept);
  if (kept == 0) return Color(0.0f);
  e.dMax = std::sqrt(far2);
  Color sum(0.0f);
  if (e.dMax > 0.0f) {
    const float inv = 1.0f / e.dMax;
    for (size_t i = 0; i < kept; ++i)
      sum += (1.0f - std::sqrt(s.dist2[i]) * inv) * photons[s.indices[i]].power.color();
  } else {
    for (size_t i = 0; i < kept; ++i) sum += photons[s.indices[i]].power.color();
  }
  return sum;
}
}  // namespace

IndirectEstimate classicEstimate(const IndirectPhoton* photons, GatherScratch& scratch,
                                 size_t count, const Vec3& n, float minNormalCos) {
  IndirectEstimate e;
  Color sum = coneSum(photons, scratch, count, n, minNormalCos, e);
  if (e.found > 0) e.value = sum / static_cast<float>(e.found);
  return e;
}

IndirectEstimate densityEstimate(const IndirectPhoton* photons, GatherScratch& scratch,
                                 size_t count, const Vec3& n, float minNormalCos) {
  IndirectEstimate e;
  Color sum = coneSum(photons, scratch, count, n, minNormalCos, e);
  constexpr float kConeNorm = 1.0f - 2.0f / 3.0f;
  // Photons a hair apart would underflow the area to 0 (or a denormal): treat that
  // like d_max = 0 rather than return inf.
  const float area = kConeNorm * kPi * e.dMax * e.dMax;
  if (area >= std::numeric_limits<float>::min()) e.value = sum / area;
  return e;
}

}  // namespace penumbra
