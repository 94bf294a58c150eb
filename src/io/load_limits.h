// What loading a scene may cost before it is refused: the bytes its files may make
// the loader allocate (the render's memory budget), and the size of any file read whole.
#pragma once
#include <cstdint>
#include <string>

namespace penumbra {

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
