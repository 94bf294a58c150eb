// The furnace: a closed Lambert sphere around a point light, whose direct and indirect
// radiance are known in closed form (the pipeline tests' analytic room).
#pragma once

namespace penumbra::testing {

// A closed Lambert sphere (rho 0.5, radius 1.5) with a point light (I = 2 W/sr) at its
// centre and the camera beside it, looking at the wall with a wide field of view.
inline const char* kFurnace = R"({
  "name": "furnace",
  "camera": {"position": [0.05, 0.02, 0.03], "look_at": [0, 0, -1], "up": [0, 1, 0], "fov": 120,
             "width": 64, "height": 48, "spp": 1},
  "lights": [{"type": "point", "position": [0, 0, 0], "color": [1, 1, 1], "intensity": 2}],
  "materials": {"wall": {"diffuse": 0.5}},
  "objects": [{"type": "sphere", "center": [0, 0, 0], "radius": 1.5, "material": "wall"}],
  "render": {"model": "physical", "seed": 3},
  "photons": {"shadow": 20000, "global": 500000, "caustic": 0, "max_bounces": 64}
})";

}  // namespace penumbra::testing
