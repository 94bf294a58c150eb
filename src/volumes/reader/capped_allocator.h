// The reader process's allocation cap: every operator new counts the bytes it holds, and
// one that would pass the cap throws std::bad_alloc (OpenVDB sizes strings, metadata and
// buffers from the file before reading them).
#pragma once
#include <cstdint>

namespace penumbra::volumes {

// The most bytes operator new may hold at once from now on (0: no cap).
void setAllocationCap(uint64_t bytes);

}  // namespace penumbra::volumes
