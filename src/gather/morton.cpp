// Morton codes and the deterministic storage order (a coarse spatial counting sort).
#include "gather/morton.h"
#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>
#include <tbb/parallel_reduce.h>
#include <algorithm>

namespace penumbra {

uint64_t spreadBits21(uint32_t v) {
  uint64_t x = v & 0x1FFFFFu;
  x = (x | (x << 32)) & 0x1F00000000FFFFull;
  x = (x | (x << 16)) & 0x1F0000FF0000FFull;
  x = (x | (x << 8)) & 0x100F00F00F00F00Full;
  x = (x | (x << 4)) & 0x10C30C30C30C30C3ull;
  x = (x | (x << 2)) & 0x1249249249249249ull;
  return x;
}

uint64_t mortonCode63(const Vec3& p, const Bounds& b) {
  constexpr float kCells = 2097151.0f;  // 2^21 - 1
  uint32_t q[3];
  for (int a = 0; a < 3; ++a) {
    float extent = b.hi[a] - b.lo[a];
    float t = extent > 0.0f ? (p[a] - b.lo[a]) / extent : 0.0f;
    q[a] = static_cast<uint32_t>(std::clamp(t, 0.0f, 1.0f) * kCells);
  }
  return spreadBits21(q[0]) | (spreadBits21(q[1]) << 1) | (spreadBits21(q[2]) << 2);
}

Bounds computeBounds(const PositionView& pos) {
  return tbb::parallel_reduce(
      tbb::blocked_range<size_t>(0, pos.count, 1 << 14), Bounds{},
      [&](const tbb::blocked_range<size_t>& r, Bounds b) {
        for (size_t i = r.begin(); i != r.end(); ++i) b.extend(pos[i]);
        return b;
      },
      [](Bounds a, const Bounds& b) {
        a.extend(b);
        return a;
      });
}

std::vector<uint32_t> storageOrder(const PositionView& pos, const uint16_t* groups,
                                   size_t groupStride, bool spatial, const Bounds& bounds) {
  const size_t n = pos.count;
  auto groupOf = [&](size_t i) -> uint32_t {
    return groups ? *reinterpret_cast<const uint16_t*>(
                        reinterpret_cast<const unsigned char*>(groups) + i * groupStride)
                  : 0u;
  };
  uint32_t numGroups = 1;
  for (size_t i = 0; i < n && groups; ++i) numGroups = std::max(numGroups, groupOf(i) + 1);
  // Buckets: (group, the top bits of the Morton code). The KD-tree build later puts
  // every photon in leaf order, so the spatial sort need only be coarse: cells of
  // 1/64 of the box per axis (fewer with many groups) give compact, balanced parts
  // and a cache-friendly build. A stable counting sort: O(n), unique result.
  int bitsPerAxis = spatial ? 6 : 0;
  while (bitsPerAxis > 0 && (uint64_t(numGroups) << (3 * bitsPerAxis)) > (uint64_t(1) << 22)) --bitsPerAxis;
  const int cellBits = 3 * bitsPerAxis;
  std::vector<uint32_t> bucket(n);
  tbb::parallel_for(tbb::blocked_range<size_t>(0, n, 1 << 14), [&](const auto& r) {
    for (size_t i = r.begin(); i != r.end(); ++i) {
      const uint64_t cell = cellBits ? mortonCode63(pos[i], bounds) >> (63 - cellBits) : 0;
      bucket[i] = static_cast<uint32_t>((uint64_t(groupOf(i)) << cellBits) | cell);
    }
  });
  std::vector<uint32_t> start((size_t(numGroups) << cellBits) + 1, 0);
  for (size_t i = 0; i < n; ++i) ++start[bucket[i] + 1];
  for (size_t b = 1; b < start.size(); ++b) start[b] += start[b - 1];
  std::vector<uint32_t> order(n);
  for (size_t i = 0; i < n; ++i) order[start[bucket[i]]++] = static_cast<uint32_t>(i);
  return order;
}

}  // namespace penumbra
