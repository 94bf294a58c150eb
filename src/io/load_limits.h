// What loading a scene may cost before it is refused: the bytes its files may make
// the loader allocate (the render's memory budget), and the size of any file read whole.
#pragma once
#include <cstdint>
#include <string>

namespace penumbra {

// The most voxels a density grid (io/vdb_reader.h) may resample into: 2^27 floats,
// 512 MiB, four times a 320^3 smoke simulation. Checked from the grid's bounding box
// before anything is allocated, so a file claiming more is refused, not attempted.
inline constexpr uint64_t kMaxDensityVoxels = uint64_t(1) << 27;

struct LoadLimits {
  // Bytes the loaded scene may allocate (meshes, buffers, decoded images): the
  // render's --max-memory or the memory available; 0: not checked.
  uint64_t maxBytes = 0;
  std::string budgetName = "available memory";  // named in a refusal: "--max-memory"
  // What the process holds before any scene data (the resource estimate's base): a
  // reader that allocates one large block (an environment map) counts it too.
  uint64_t heldBytes = 0;
};

}  // namespace penumbra
