// Analytic spheres as one Embree user geometry: exact hits from outside and
// inside (a ray born inside a glass ball must find the far wall). The geometry
// itself is created behind the seam (createSphereGeometry, geometry/embree_impl.h).
#pragma once
#include "core/scene.h"

namespace penumbra {

// Nearest root of |o + t d - c| = r in (tMin, tMax), or a negative value if none.
// Solved in double with the cancellation-free form of Ray Tracing Gems ch. 7.
double intersectSphere(const Sphere& s, const Vec3& o, const Vec3& d, double tMin, double tMax);

}  // namespace penumbra
