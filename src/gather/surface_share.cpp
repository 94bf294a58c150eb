// The gather disc's share on the query's surface, cut by neighbouring surfaces' planes.
#include "gather/surface_share.h"
#include "gather/indirect_estimate.h"
#include <algorithm>
#include <cmath>

namespace penumbra {
namespace {

// Two cuts whose directions are closer than 45 degrees are one edge.
constexpr float kSameEdgeCos = 0.7071f;
// Distances below this share of the radius are the edge itself, to rounding.
constexpr float kOnEdge = 1e-4f;
// Two photons are on one plane with normals within 0.8 degrees and the second within
// kCoplanar radii of the first's plane; kConfirmSpan radii apart they confirm it.
constexpr float kSamePlaneCos = 0.9999f, kCoplanar = 1e-3f, kConfirmSpan = 0.1f;

}  // namespace

double kernelMassBeyond(double d) {
  if (d >= 1.0) return 0.0;
  d = std::max(d, 0.0);
  // K = 2 / pi (1 - x^2 - y^2) on the unit disc; across the chord x = d its mass is
  // 8 / (3 pi) times the integral of (1 - x^2)^(3/2) from d to 1.
  const double h = std::sqrt(1.0 - d * d);
  const double g = d * h * h * h / 4.0 + 3.0 * d * h / 8.0 + 3.0 * std::asin(d) / 8.0;
  return 0.5 - 8.0 / (3.0 * kPi) * g;
}

void SurfaceCuts::add(const Vec3& position, const Vec3& normal, float cos) {
  if (!(std::abs(cos) < kIndirectMinNormalCos)) return;  // the surface itself, or facing away
  // A plane farther than the radius (in the tangent plane) cuts nothing.
  if (!(std::abs(glm::dot(p_ - position, normal)) < radius_ * glm::length(normal - cos * ng_))) return;
  for (int i = 0; i < planeCount_; ++i) {
    Plane& plane = planes_[i];
    const Vec3 offset = position - plane.point;
    if (glm::dot(normal, plane.normal) > kSamePlaneCos &&
        std::abs(glm::dot(offset, plane.normal)) <= kCoplanar * radius_) {
      plane.confirmed = plane.confirmed || glm::length(offset) >= kConfirmSpan * radius_;
      return;
    }
  }
  if (planeCount_ < kMaxPlanes) planes_[planeCount_++] = {position, normal, false};
}

void SurfaceCuts::finish() {
  for (int i = 0; i < planeCount_; ++i)
    if (planes_[i].confirmed) cut(planes_[i]);
}

void SurfaceCuts::cut(const Plane& plane) {
  // Signed distance s of the query from the plane. In the tangent plane the surface
  // keeps the query's side, t . nt > -s with nt the normal's tangent part (|nt| >=
  // sin 60 degrees), so the line lies |s| / |nt| away, along -sign(s) nt.
  const float s = glm::dot(p_ - plane.point, plane.normal);
  const Vec3 nt = plane.normal - glm::dot(plane.normal, ng_) * ng_;
  const float len = glm::length(nt);
  const float d = std::abs(s) / len;
  // A query on the edge itself (s within rounding of 0) keeps the side the normal
  // points to if the plane's photon stands above its surface (a concave edge), the
  // other if below (convex); a photon on the line itself says nothing.
  float side = s;
  if (std::abs(s) <= kOnEdge * radius_) {
    const float h = glm::dot(plane.point - p_, ng_);
    if (std::abs(h) <= kOnEdge * radius_) return;
    side = h;
  }
  const Vec3 dir = nt * ((side > 0.0f ? -1.0f : 1.0f) / len);
  for (int c = 0; c < count_; ++c) {
    if (glm::dot(dir, dir_[c]) > kSameEdgeCos) {
      if (d < dist_[c]) {
        dist_[c] = d;
        dir_[c] = dir;
      }
      return;
    }
  }
  if (count_ < kMaxCuts) {
    dir_[count_] = dir;
    dist_[count_++] = d;
    return;
  }
  // A fourth direction: it replaces the farthest cut.
  int far = 0;
  for (int c = 1; c < count_; ++c) far = dist_[c] > dist_[far] ? c : far;
  if (d < dist_[far]) {
    dist_[far] = d;
    dir_[far] = dir;
  }
}

bool SurfaceCuts::keeps(const Vec3& position) const {
  const Vec3 d = position - p_;
  for (int c = 0; c < count_; ++c)
    if (!(glm::dot(d, dir_[c]) < dist_[c])) return false;
  return true;
}

float SurfaceCuts::shareAt(float radius) const {
  double share = 1.0;
  for (int c = 0; c < count_; ++c) share *= 1.0 - kernelMassBeyond(dist_[c] / radius);
  return static_cast<float>(share);
}

}  // namespace penumbra
