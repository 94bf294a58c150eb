// Anonymous mappings for photon arrays: below 2 MB populated up front (4 KB pages),
// from 2 MB on 2 MB-aligned and backed by transparent huge pages where the kernel allows.
#include "core/populated_memory.h"
#include <sys/mman.h>
#include <cstdint>
#include <new>

namespace penumbra {
namespace {
constexpr size_t kHugePage = size_t(2) << 20;
}  // namespace

void* allocatePopulated(size_t bytes) {
  if (bytes == 0) return nullptr;
  if (bytes < kHugePage) {
    void* p = mmap(nullptr, bytes, PROT_READ | PROT_WRITE, MAP_PRIVATE | MAP_ANONYMOUS | MAP_POPULATE, -1, 0);
    if (p == MAP_FAILED) throw std::bad_alloc();
    return p;
  }
  // Over-map by one huge page, keep the 2 MB-aligned part: huge pages need the alignment.
  const size_t mapped = bytes + kHugePage;
  void* raw = mmap(nullptr, mapped, PROT_READ | PROT_WRITE, MAP_PRIVATE | MAP_ANONYMOUS | MAP_NORESERVE, -1, 0);
  if (raw == MAP_FAILED) throw std::bad_alloc();
  const uintptr_t start = reinterpret_cast<uintptr_t>(raw);
  const uintptr_t aligned = (start + kHugePage - 1) & ~uintptr_t(kHugePage - 1);
  if (aligned > start) munmap(raw, aligned - start);
  const uintptr_t end = aligned + bytes, mappedEnd = start + mapped;
  if (mappedEnd > end) munmap(reinterpret_cast<void*>(end), mappedEnd - end);
  void* p = reinterpret_cast<void*>(aligned);
  // Advice only, refused where THP is off (then 4 KB pages fault in as written). Not
  // populated: a huge page faults in once per 2 MB where it is written, and an
  // emitter's block is written only as far as its batches reach.
  madvise(p, bytes, MADV_HUGEPAGE);
  return p;
}

void freePopulated(void* p, size_t bytes) noexcept {
  if (p) munmap(p, bytes);
}

}  // namespace penumbra
