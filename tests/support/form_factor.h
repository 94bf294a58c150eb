// Analytic form factors for the area-light tests: a point to an axis-aligned
// rectangle in a parallel plane (Howell's catalogue, configuration B-3).
#pragma once
#include "support/physical_fixtures.h"
#include <cmath>

namespace penumbra::testing {

// From a point to a rectangle [0,a] x [0,b] in a parallel plane at distance c, the
// point below the corner.
inline double cornerFactor(double a, double b, double c) {
  const double A = a / c, B = b / c, sa = std::sqrt(1 + A * A), sb = std::sqrt(1 + B * B);
  return (A / sa * std::atan(B / sa) + B / sb * std::atan(A / sb)) / (2.0 * kPiD);
}
inline double signedCorner(double x, double z, double c) {
  const double s = (x < 0 ? -1.0 : 1.0) * (z < 0 ? -1.0 : 1.0);
  return s * cornerFactor(std::abs(x), std::abs(z), c);
}
// The rectangle [x0,x1] x [z0,z1] (relative to the point) by inclusion-exclusion.
inline double rectFactor(double x0, double x1, double z0, double z1, double c) {
  return signedCorner(x1, z1, c) - signedCorner(x0, z1, c) - signedCorner(x1, z0, c) + signedCorner(x0, z0, c);
}

}  // namespace penumbra::testing
