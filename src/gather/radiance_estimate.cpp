// Photon radiance estimate; finite for any input (empty maps, coincident photons).
#include "gather/radiance_estimate.h"
#include "gather/indirect_estimate.h"
#include "gather/knn_result_sets.h"
#include "gather/surface_share.h"
#include <algorithm>
#include <cmath>

namespace penumbra {

namespace {

bool lambertian(const Bsdf& bsdf) { return bsdf.type == BsdfType::Opaque && !(bsdfFlags(bsdf) & kBsdfGlossy); }
Color lambertFactor(const Bsdf& bsdf) { return (1.0f - bsdf.kr) * bsdf.diffuse * (1.0f / kPi); }

struct PhotonSum {
  Color sum{0.0f};
  Color inner{0.0f};  // the same over the inner disc (r / sqrt 2), when asked
  int found = 0;
};

// The inner disc's kernel weight at squared distance d2 (invInnerR2 = 2 / r^2), <= 0 outside it.
inline float innerWeight(float d2, float invInnerR2) { return 1.0f - d2 * invInnerR2; }

// The kernel-weighted sum over the gathered photons on the query's surface: those
// whose normal agrees with frame.ng and, when `keep` is given, that lie on the
// query's side of its cuts. Photons at an angle to the surface go to `record`.
// With invInnerR2 > 0, `inner` sums the inner disc's kernel too.
PhotonSum sumPhotons(const IndirectPhotonMap& map, const GatherScratch& s, size_t n, float invR2, float invInnerR2,
                     const Bsdf& bsdf, const BsdfFrame& frame, const NormalFilter& filter, const Vec3& wo,
                     SurfaceCuts* record, const SurfaceCuts* keep) {
  // A purely Lambertian BSDF is one constant: weigh the power first, multiply once.
  const bool lambertOnly = lambertian(bsdf);
  const PhotonArray<IndirectPhoton>& photons = map.photons();
  PhotonSum a;
  for (size_t i = 0; i < n; ++i) {
    const IndirectPhoton& ph = photons[s.indices[i]];
    if (!filter.passesAsOwn(ph.normal)) {
      const Vec3 normal = decodeOctahedral(ph.normal);
      const float cos = glm::dot(normal, frame.ng);
      if (cos <= kIndirectMinNormalCos) {
        if (record) record->add(ph.position, normal, cos);
        continue;
      }
    }
    const float w = 1.0f - s.dist2[i] * invR2;
    if (w <= 0.0f || (keep && !keep->keeps(ph.position))) continue;
    ++a.found;
    const float wInner = invInnerR2 > 0.0f ? innerWeight(s.dist2[i], invInnerR2) : 0.0f;
    if (lambertOnly) {
      const Color power = ph.power.color();  // decoded once per photon on either path
      a.sum += w * power;
      if (wInner > 0.0f) a.inner += wInner * power;
      continue;
    }
    const Vec3 wi = -decodeOctahedral(ph.direction);
    const float cosI = glm::dot(frame.ns, wi);
    if (cosI <= 1e-4f) continue;
    const Color power = ph.power.color(), f = evaluateBsdf(bsdf, frame, wo, wi);
    a.sum += w * power * f / cosI;
    if (wInner > 0.0f) a.inner += wInner * power * f / cosI;
  }
  if (lambertOnly) a.sum *= lambertFactor(bsdf), a.inner *= lambertFactor(bsdf);
  return a;
}

// The Lambertian kernel-weighted power when every photon passes the normal filter, in
// fixed point: integer additions do not depend on the order the search returned the
// photons in, so the gather needs no sort. Each term is w <= 1 times a colour below
// 2^8 x 2^(e - 136) (e: the map's largest exponent byte), scaled below 2^36: 2^27
// terms stay inside int64. Returns false, having summed nothing, when a photon fails
// the filter: the caller then sorts, and photons at an angle mark the surface's edges.
bool sumOnPlane(const IndirectPhotonMap& map, const GatherScratch& s, size_t n, float invR2, float invInnerR2,
                const NormalFilter& filter, PhotonSum& a) {
  const PhotonArray<IndirectPhoton>& photons = map.photons();
  const double scale = std::ldexp(1.0, 136 + 28 - static_cast<int>(map.topPowerExponent()));
  int64_t sum[3] = {0, 0, 0}, inner[3] = {0, 0, 0};
  int found = 0;
  for (size_t i = 0; i < n; ++i) {
    const IndirectPhoton& ph = photons[s.indices[i]];
    if (!filter.passes(ph.normal)) return false;
    const float w = 1.0f - s.dist2[i] * invR2;
    if (w <= 0.0f) continue;
    ++found;
    const Color power = ph.power.color();
    const Color c = w * power;
    for (int ch = 0; ch < 3; ++ch) sum[ch] += static_cast<int64_t>(double(c[ch]) * scale + 0.5);
    const float wInner = invInnerR2 > 0.0f ? innerWeight(s.dist2[i], invInnerR2) : 0.0f;
    if (wInner <= 0.0f) continue;
    const Color ci = wInner * power;
    for (int ch = 0; ch < 3; ++ch) inner[ch] += static_cast<int64_t>(double(ci[ch]) * scale + 0.5);
  }
  a.found = found;
  for (int ch = 0; ch < 3; ++ch) {
    a.sum[ch] = static_cast<float>(double(sum[ch]) / scale);
    a.inner[ch] = static_cast<float>(double(inner[ch]) / scale);
  }
  return true;
}

}  // namespace

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
    // Unsorted: its order depends on the search's hints (per thread), so a sum below
    // is either order-independent or taken after sorting into the canonical order.
    n = map.knn(p, static_cast<size_t>(gather.k), maxRadius, s, false);
    r2 = 0.0f;
    for (size_t i = 0; i < n; ++i) r2 = std::max(r2, s.dist2[i]);
    // Fewer than k inside the bound: the k-th lies beyond it, the disc is the bound's.
    if (maxRadius > 0.0f && n < static_cast<size_t>(gather.k)) r2 = maxRadius * maxRadius;
  }
  if (n == 0 || !(r2 >= std::numeric_limits<float>::min())) return e;
  e.radius = std::sqrt(r2);
  const float invR2 = 1.0f / r2;
  // The inner disc has half the area: its kernel 2 / (pi r^2 / 2) (1 - d^2 / (r^2 / 2)).
  const float invInnerR2 = gather.probeSmoothing ? 2.0f * invR2 : 0.0f;
  const NormalFilter filter(frame.ng, kIndirectMinNormalCos);  // frame.ng's code, found once
  PhotonSum plane;
  if (lambertian(bsdf) && sumOnPlane(map, s, n, invR2, invInnerR2, filter, plane)) {
    e.found = plane.found;
    e.value = plane.sum * lambertFactor(bsdf) * (2.0f / kPi * invR2);
    if (gather.probeSmoothing) e.smoothing = 2.0f * (e.value - plane.inner * lambertFactor(bsdf) * (2.0f / kPi * invInnerR2));
    return e;
  }
  if (gather.k > 0) knn::sortGathered(s, n);
  SurfaceCuts cuts(p, frame.ng, e.radius);
  PhotonSum a = sumPhotons(map, s, n, invR2, invInnerR2, bsdf, frame, filter, wo, &cuts, nullptr);
  cuts.finish();
  float innerShare = 1.0f;
  if (cuts.count() > 0) {
    // Near an edge: only the photons on the query's side, over the kernel's mass there.
    a = sumPhotons(map, s, n, invR2, invInnerR2, bsdf, frame, filter, wo, nullptr, &cuts);
    a.sum /= cuts.share();
    innerShare = gather.probeSmoothing ? cuts.shareAt(e.radius * std::sqrt(0.5f)) : 1.0f;
  }
  e.found = a.found;
  e.value = a.sum * (2.0f / kPi * invR2);
  if (gather.probeSmoothing && innerShare > 0.0f) e.smoothing = 2.0f * (e.value - a.inner / innerShare * (2.0f / kPi * invInnerR2));
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
