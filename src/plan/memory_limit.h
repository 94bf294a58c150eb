// The memory a render may use: --max-memory SIZE, or what the machine has free,
// and the refusal (exit 2, with the estimate) of a job that would not fit.
#pragma once
#include "plan/resource_estimate.h"
#include "io/load_limits.h"
#include <cstdint>
#include <string>

namespace penumbra {

// "8G", "512M", "1.5GiB", "2048" (bytes): binary units, case-insensitive. Throws
// InputError naming `option` for anything else or for zero.
uint64_t parseMemorySize(const std::string& text, const std::string& option = "--max-memory");

// MemAvailable from /proc/meminfo plus what this process already holds (its scene
// is loaded by the time we ask), else physical pages x page size; 0 if unknown.
uint64_t availableMemoryBytes();

struct MemoryLimit {
  uint64_t bytes = 0;  // 0: unknown, nothing is refused
  std::string name;    // "--max-memory" or "available memory"
};

// `requested` bytes (--max-memory), or 0 for what the machine has available now.
MemoryLimit memoryLimit(uint64_t requested);

// The same limit for loading: what a scene's files may make the loader allocate.
LoadLimits loadLimits(uint64_t requested);

// Throws InputError "<scene>: needs ~X (...) but <limit> is Y" when the estimate
// exceeds the limit.
void checkMemory(const ResourceEstimate& estimate, const MemoryLimit& limit,
                 const std::string& sceneFile);

}  // namespace penumbra
