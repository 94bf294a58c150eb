// Morton codes and the parallel, deterministic storage-order sort.
#include "gather/morton.h"
#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>
#include <tbb/parallel_reduce.h>
#include <tbb/parallel_sort.h>
#include <numeric>

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

namespace {
struct SortKey {
  uint64_t code;
  uint32_t group;
  uint32_t index;
  bool operator<(const SortKey& o) const {
    if (group != o.group) return group < o.group;
    if (code != o.code) return code < o.code;
    return index < o.index;
  }
};
}  // namespace

std::vector<uint32_t> storageOrder(const PositionView& pos, const uint16_t* groups,
                                   size_t groupStride, bool spatial, const Bounds& bounds) {
  const size_t n = pos.count;
  auto groupOf = [&](size_t i) -> uint32_t {
    return groups ? *reinterpret_cast<const uint16_t*>(
                        reinterpret_cast<const unsigned char*>(groups) + i * groupStride)
                  : 0u;
  };
  std::vector<uint32_t> order(n);
  if (!spatial) {
    // Stable counting partition by group: O(n), keeps the emission order inside.
    std::vector<size_t> start(size_t(1) << 16, 0);
    for (size_t i = 0; i < n; ++i) ++start[groupOf(i)];
    size_t sum = 0;
    for (size_t& s : start) { size_t c = s; s = sum; sum += c; }
    for (size_t i = 0; i < n; ++i) order[start[groupOf(i)]++] = static_cast<uint32_t>(i);
    return order;
  }
  std::vector<SortKey> keys(n);
  tbb::parallel_for(tbb::blocked_range<size_t>(0, n, 1 << 14), [&](const auto& r) {
    for (size_t i = r.begin(); i != r.end(); ++i)
      keys[i] = {mortonCode63(pos[i], bounds), groupOf(i), static_cast<uint32_t>(i)};
  });
  tbb::parallel_sort(keys.begin(), keys.end());
  tbb::parallel_for(tbb::blocked_range<size_t>(0, n, 1 << 14), [&](const auto& r) {
    for (size_t i = r.begin(); i != r.end(); ++i) order[i] = keys[i].index;
  });
  return order;
}

}  // namespace penumbra
