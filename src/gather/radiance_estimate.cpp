// Photon radiance estimate; finite for any input (empty maps, coincident photons).
#include "gather/radiance_estimate.h"
#include "gather/indirect_estimate.h"
#include <algorithm>
#include <cmath>

namespace penumbra {

RadianceEstimate photonRadiance(const IndirectPhotonMap& map, const Bsdf& bsdf, const BsdfFrame& frame,
                                const Vec3& p, const Vec3& wo, const PhotonGather& gather, GatherScratch& s) {
  RadianceEstimate e;
  const float maxRadius = std::max(gather.maxRadius, 0.0f);
  if (map.empty() || (maxRadius == 0.0f && gather.k <= 0)) return e;
  size_t n;
  float r2;
  if (gather.k <= 0) {
    n = map.within(p, maxRadius, s);
    r2 = maxRadius * maxRadius;
  } else {
    // Sorted (canonical order) so the float sum is the same at any thread count.
    n = map.knn(p, static_cast<size_t>(gather.k), maxRadius, s);
    r2 = 0.0f;
    for (size_t i = 0; i < n; ++i) r2 = std::max(r2, s.dist2[i]);
    // Fewer than k inside the bound: the k-th lies beyond it, the disc is the bound's.
    if (maxRadius > 0.0f && n < static_cast<size_t>(gather.k)) r2 = maxRadius * maxRadius;
  }
  if (n == 0 || !(r2 >= std::numeric_limits<float>::min())) return e;
  e.radius = std::sqrt(r2);
  // A purely Lambertian BSDF is one constant: weigh the power first, multiply once.
  const bool lambertOnly = bsdf.type == BsdfType::Opaque && !(bsdfFlags(bsdf) & kBsdfGlossy);
  const PhotonArray<IndirectPhoton>& photons = map.photons();
  const float invR2 = 1.0f / r2;
  Color sum(0.0f);
  int found = 0;
  for (size_t i = 0; i < n; ++i) {
    const IndirectPhoton& ph = photons[s.indices[i]];
    if (glm::dot(decodeOctahedral(ph.normal), frame.ng) <= kIndirectMinNormalCos) continue;
    float w = 1.0f - s.dist2[i] * invR2;
    if (w <= 0.0f) continue;
    ++found;
    if (lambertOnly) {
      sum += w * ph.power.color();  // decoded once per photon on either path
      continue;
    }
    Vec3 wi = -decodeOctahedral(ph.direction);
    float cosI = glm::dot(frame.ns, wi);
    if (cosI <= 1e-4f) continue;
    sum += w * ph.power.color() * evaluateBsdf(bsdf, frame, wo, wi) / cosI;
  }
  if (lambertOnly) sum *= (1.0f - bsdf.kr) * bsdf.diffuse * (1.0f / kPi);
  e.found = found;
  e.value = sum * (2.0f / kPi * invR2);
  return e;
}

float typicalKnnRadius(const IndirectPhotonMap& map, int k, GatherScratch& s) {
  const size_t n = map.size();
  if (n == 0 || k <= 0) return 0.0f;
  const size_t probes = std::min<size_t>(256, n), step = n / probes;
  std::vector<float> radii;
  for (size_t i = 0; i < probes; ++i) {
    size_t found = map.knn(map.photons()[i * step].position, static_cast<size_t>(k), 0.0f, s);
    float r2 = 0.0f;
    for (size_t j = 0; j < found; ++j) r2 = std::max(r2, s.dist2[j]);
    radii.push_back(std::sqrt(r2));
  }
  std::nth_element(radii.begin(), radii.begin() + radii.size() / 2, radii.end());
  return radii[radii.size() / 2];
}

double passRadiusShare(uint32_t pass, float alpha) {
  // The product is Gamma(i + 1 + alpha) / (Gamma(1 + alpha) Gamma(i + 2)).
  const double a = alpha, i = pass;
  return std::exp(std::lgamma(i + 1.0 + a) - std::lgamma(1.0 + a) - std::lgamma(i + 2.0));
}

int passK(int k, uint32_t pass, float alpha) {
  if (k <= kMinPassK) return k;
  return std::max(kMinPassK, static_cast<int>(std::lround(k * passRadiusShare(pass, alpha))));
}

}  // namespace penumbra
