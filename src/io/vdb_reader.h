// Density grids from OpenVDB files, through the module core/density_codec.h loads: the
// named float grid (or the first one), its active box resampled into a dense lattice.
#pragma once
#include "core/density_codec.h"
#include "core/scene.h"
#include "io/json_reader.h"
#include <memory>
#include <stdexcept>
#include <string>

namespace penumbra {

// A .vdb that cannot become a density grid; what() is the problem, without the path.
struct VdbError : std::runtime_error {
  using std::runtime_error::runtime_error;
};

// `path` read by the OpenVDB module (core/density_codec.h says what it checks), after
// io's own check that the file can be opened. Throws VdbError.
DensityGrid loadDensityGrid(const std::string& path, const DensityRequest& request);

// A medium's "density": {"file", "grid", "scale", "transform"} read into a grid within
// the scene's limits; the file joins Scene::inputs. Refuses at the node in one line.
std::shared_ptr<const DensityGrid> readDensity(const JsonNode& density, Scene& scene);

}  // namespace penumbra
