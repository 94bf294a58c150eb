// Density grids from OpenVDB files: the named float grid (or the first one), its active
// box resampled into a dense core/media/density_grid.h lattice in world space.
#pragma once
#include "core/media/density_grid.h"
#include "core/scene.h"
#include "io/json_reader.h"
#include <glm/mat4x4.hpp>
#include <memory>
#include <stdexcept>
#include <string>

namespace penumbra {

// A .vdb that cannot become a density grid; what() is the problem, without the path.
struct VdbError : std::runtime_error {
  using std::runtime_error::runtime_error;
};

struct VdbRequest {
  std::string grid;                 // empty: the first float grid in the file
  double scale = 1.0;               // multiplies every value
  glm::dmat4 objectToWorld{1.0};    // after the grid's own index-to-world transform
  uint64_t maxVoxels = 0;           // the dense lattice's limit (kMaxDensityVoxels)
  uint64_t maxBytes = 0;            // the load budget (0: unchecked)
};

// Reads and checks `path`: a VDB, the grid (float, linear transform), the lattice within
// the limits before it is allocated, every value finite and >= 0. Throws VdbError.
DensityGrid loadDensityGrid(const std::string& path, const VdbRequest& request);

// A medium's "density": {"file", "grid", "scale", "transform"} read into a grid; the file
// joins Scene::inputs. Refuses at the node in one line.
std::shared_ptr<const DensityGrid> readDensity(const JsonNode& density, Scene& scene);

}  // namespace penumbra
