// Participating media as loaded data: absorption and scattering per unit length, a
// Henyey–Greenstein phase, emission, and an optional density grid scaling all three.
#pragma once
#include "core/math.h"
#include <memory>
#include <string>

namespace penumbra {

struct DensityGrid;  // core/media/density_grid.h

inline constexpr int kNoMedium = -1;  // vacuum: a ray travels unattenuated

struct Medium {
  std::string name;
  Color sigmaA{0.0f};    // absorption coefficient, per scene unit
  Color sigmaS{0.0f};    // scattering coefficient, per scene unit
  float g = 0.0f;        // Henyey–Greenstein asymmetry in (-1, 1): > 0 scatters forwards
  Color emission{0.0f};  // emitted radiance Le: the medium adds sigmaA x Le per unit length
  // Heterogeneous media: sigmaA, sigmaS and the emission at a point are scaled by the
  // grid's density there (null: homogeneous, density 1 everywhere).
  std::shared_ptr<const DensityGrid> density;
  Color sigmaT() const { return sigmaA + sigmaS; }
  bool homogeneous() const { return !density; }
};

// Which media an object's surface separates. A closed object (sphere, box, closed mesh)
// in a scene with media always separates its inside (its own medium, or vacuum) from
// what surrounds it; an open surface leaves a crossing ray in the medium it was in.
struct MediumInterface {
  int inside = kNoMedium;
  int outside = kNoMedium;
  bool separates = false;  // false: the surface does not change a ray's medium
  bool inward = false;     // a closed mesh wound inwards: its winding normal points inside
  // Whether a ray arriving on the winding normal's side (frontFace) enters the inside.
  bool entersFromFront() const { return !inward; }
};

}  // namespace penumbra
