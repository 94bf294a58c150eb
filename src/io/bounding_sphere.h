// A ball enclosing a set of points and balls (a model's vertices and spheres), the
// shape the framing camera fits to the image: a few linear passes, no copy of the points.
#pragma once
#include <glm/geometric.hpp>
#include <glm/vec3.hpp>
#include <algorithm>

namespace penumbra {

struct BoundingSphere {
  glm::dvec3 centre{0.0};
  double radius = -1.0;  // < 0: nothing enclosed
  bool empty() const { return radius < 0.0; }
};

// The smaller of two enclosing balls: Ritter's (the pair of far points found from an
// arbitrary item spans the first ball, which grows to take in every item) and the ball
// about the bounding box's centre through the farthest item. Neither is the minimal
// ball in general, each is within a few percent of it on round and boxy models, and
// both enclose every item exactly (the radius is rounded up). `forEach(f)` calls
// f(centre, radius) for every item (a point: radius 0), the same items each time.
template <class ForEach>
BoundingSphere boundingSphere(const ForEach& forEach) {
  using glm::dvec3;
  // The point of ball (c, r) farthest from `from`.
  auto farPoint = [](const dvec3& from, const dvec3& c, double r) {
    const double d = glm::length(c - from);
    return d > 0.0 ? c + (c - from) * (r / d) : c + dvec3(r, 0.0, 0.0);
  };
  bool any = false;
  dvec3 first(0.0), lo(1e308), hi(-1e308);
  forEach([&](const dvec3& c, double r) {
    if (!any) first = c;
    any = true;
    lo = glm::min(lo, c - dvec3(r));
    hi = glm::max(hi, c + dvec3(r));
  });
  if (!any) return {};
  auto farthestFrom = [&](const dvec3& from) {
    dvec3 best = from;
    double bestDistance = -1.0;
    forEach([&](const dvec3& c, double r) {
      const dvec3 p = farPoint(from, c, r);
      const double d = glm::length(p - from);
      if (d > bestDistance) bestDistance = d, best = p;
    });
    return best;
  };
  const dvec3 b = farthestFrom(first), d = farthestFrom(b);
  BoundingSphere ritter{0.5 * (b + d), 0.5 * glm::length(d - b)};
  BoundingSphere boxed{0.5 * (lo + hi), 0.0};
  forEach([&](const dvec3& c, double r) {
    const double out = glm::length(c - ritter.centre);
    if (out + ritter.radius <= r) {  // the item's ball holds the whole ball so far
      ritter = {c, r};
    } else if (out + r > ritter.radius) {
      const double grown = 0.5 * (ritter.radius + out + r);
      if (out > 0.0) ritter.centre += (c - ritter.centre) * ((grown - ritter.radius) / out);
      ritter.radius = grown;
    }
    boxed.radius = std::max(boxed.radius, glm::length(c - boxed.centre) + r);
  });
  BoundingSphere s = ritter.radius <= boxed.radius ? ritter : boxed;
  // The moved centre and the sums round: a relative 1e-9 more keeps every item inside.
  s.radius *= 1.0 + 1e-9;
  return s;
}

}  // namespace penumbra
