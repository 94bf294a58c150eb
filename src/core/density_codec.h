// The seam to OpenVDB: a shared module (src/volumes) reads .vdb files into density
// grids, inside a reader process of its own (src/volumes/reader): OpenVDB trusts the
// lengths a file states, so a damaged file may ask it for gigabytes, crash it or loop;
// the process has a memory cap and a deadline, and whatever happens to it, the caller
// gets a problem in words. A run without a density grid never starts it.
#pragma once
#include "core/media/density_grid.h"
#include <glm/mat4x4.hpp>
#include <cstdint>
#include <limits>
#include <string>

namespace penumbra {

struct DensityRequest {
  std::string grid;                 // empty: the first float grid in the file
  double scale = 1.0;               // multiplies every value
  glm::dmat4 objectToWorld{1.0};    // after the grid's own index-to-world transform
  uint64_t maxVoxels = 0;           // the dense lattice's limit (io/load_limits.h)
  uint64_t maxBytes = 0;            // the load budget (0: unchecked)
  // The scene's limits (io/float_checks.h): the largest density after the scale and
  // the largest |coordinate| of the grid's world box.
  double maxValue = std::numeric_limits<double>::infinity();
  double maxCoordinate = std::numeric_limits<double>::infinity();
};

class DensityCodec {
 public:
  virtual ~DensityCodec() = default;
  // Reads and checks `path`: a VDB, the grid (float, linear transform), the lattice
  // within the limits before it is allocated, every value finite and >= 0. Returns ""
  // with `out` filled, or the problem in words (without the path).
  virtual std::string load(const std::string& path, const DensityRequest& request, DensityGrid& out) const = 0;
};

inline constexpr const char* kDensityCodecEntry = "penumbra_density_codec";
inline constexpr const char* kVolumeModuleName = "libpenumbra_volumes.so";
inline constexpr const char* kVolumeReaderName = "penumbra-volumes";

// What the reader process may allocate reading a request, in bytes: the tree, the dense
// lattice and its copy on the way out, beside OpenVDB's own tables.
uint64_t densityMemoryCap(const DensityRequest& request);

// The reader for everything that loads a scene: each call runs the reader process
// (thread-safe); throws std::runtime_error when that process cannot be found or started.
const DensityCodec& densityCodec();
// The module itself, in this process: for the reader process only (thread-safe; throws
// std::runtime_error when the module cannot be loaded).
const DensityCodec& densityModule();

}  // namespace penumbra
