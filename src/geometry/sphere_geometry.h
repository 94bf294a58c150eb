// Analytic spheres as one Embree user geometry: exact hits from outside and
// inside (a ray born inside a glass ball must find the far wall).
#pragma once
#include "core/scene.h"
#include <embree3/rtcore.h>

namespace penumbra {

// Nearest root of |o + t d - c| = r in (tMin, tMax), or a negative value if none.
// Solved in double with the cancellation-free form of Ray Tracing Gems ch. 7.
double intersectSphere(const Sphere& s, const Vec3& o, const Vec3& d, double tMin, double tMax);

// Creates the user geometry for all scene spheres (primID = sphere index). The
// spheres vector must outlive the Embree scene.
RTCGeometry createSphereGeometry(RTCDevice device, const std::vector<Sphere>& spheres);

}  // namespace penumbra
