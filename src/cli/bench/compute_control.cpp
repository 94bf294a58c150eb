// The control's fixed work, parallelised over whatever threads TBB may use.
#include "cli/bench/compute_control.h"
#include <tbb/parallel_for.h>
#include <array>
#include <cstddef>

namespace penumbra {

uint64_t computeControl() {
  constexpr size_t kChunks = 256;
  constexpr uint64_t kStepsPerChunk = uint64_t(1) << 20;
  std::array<uint64_t, kChunks> out{};
  tbb::parallel_for(size_t(0), kChunks, [&](size_t c) {
    uint64_t a = c + 1, b = ~c;
    for (uint64_t i = 0; i < kStepsPerChunk; ++i) {
      a ^= a << 13; a ^= a >> 7; a ^= a << 17;
      b ^= b << 13; b ^= b >> 7; b ^= b << 17;
    }
    out[c] = a ^ b;
  });
  uint64_t all = 0;
  for (uint64_t v : out) all ^= v;
  return all;
}

}  // namespace penumbra
