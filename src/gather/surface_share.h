// The share of a gather disc's kernel that lies on the query's own surface: where a
// room's walls meet, or a box stands on the floor, the disc reaches past the edge.
#pragma once
#include "core/math.h"

namespace penumbra {

// Photons the normal filter leaves out because their surface stands at an angle to
// the query's (60..120 degrees, |cos| < kIndirectMinNormalCos: a neighbouring wall, a
// box's side) may lie on a plane the query's surface ends at, on the query's side of
// it, whether the edge is concave (a room's corner) or convex (a box's top). A plane
// counts once two of its photons at least a tenth of the radius apart agree on it
// (the same normal, coplanar): a flat neighbour, not a curved surface turning away
// (a teapot's body, whose tangent planes say nothing about where it ends). Each such
// plane cuts the disc along the line where it meets the query's tangent plane; cuts
// in about the same direction count once, by the nearest. share() is the Epanechnikov
// kernel's mass on the query's side of every cut (the product over directions: exact
// for one cut and for perpendicular cuts through the centre, within 1% for other
// perpendicular ones); the photons on that side over it estimate the density of the
// surface that is there. Photons facing away (a thin wall's far side) cut nothing.
class SurfaceCuts {
 public:
  SurfaceCuts(const Vec3& p, const Vec3& ng, float radius) : p_(p), ng_(ng), radius_(radius) {}
  // A photon at `position` with stored normal `normal`, cos = dot(normal, ng).
  void add(const Vec3& position, const Vec3& normal, float cos);
  // Turns the planes the photons agreed on into cuts; call once, after the last add.
  void finish();
  int count() const { return count_; }
  // Whether a point of the surface lies on the query's side of every cut.
  bool keeps(const Vec3& position) const;
  float share() const { return shareAt(radius_); }
  // The same for the kernel of another radius around the same point (the cuts stay).
  float shareAt(float radius) const;

 private:
  struct Plane {
    Vec3 point, normal;
    bool confirmed;
  };
  static constexpr int kMaxPlanes = 8, kMaxCuts = 3;
  void cut(const Plane& plane);
  Vec3 p_, ng_;
  float radius_;
  Plane planes_[kMaxPlanes];
  int planeCount_ = 0;
  Vec3 dir_[kMaxCuts];  // unit, in the tangent plane, from the query toward the line
  float dist_[kMaxCuts] = {};
  int count_ = 0;
};

// The Epanechnikov kernel's mass beyond a chord at `d` radii from the disc's centre:
// 1/2 at d = 0, 0 at d >= 1.
double kernelMassBeyond(double d);

}  // namespace penumbra
