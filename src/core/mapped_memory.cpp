// Anonymous mappings for photon arrays: below 2 MB populated up front (4 KB pages),
// from 2 MB on 2 MB-aligned and backed by transparent huge pages where the kernel allows.
#include "core/mapped_memory.h"
#include <sys/mman.h>
#include <cstdint>
#include <new>

namespace penumbra {
namespace {
constexpr size_t kPage = 4096, kHugePage = size_t(2) << 20;
size_t pageRounded(size_t bytes) { return (bytes + kPage - 1) & ~(kPage - 1); }
}  // namespace

void* mapPhotonMemory(size_t bytes) {
  if (bytes == 0) return nullptr;
  const size_t length = pageRounded(bytes);
  if (length < kHugePage) {
    void* p = mmap(nullptr, length, PROT_READ | PROT_WRITE, MAP_PRIVATE | MAP_ANONYMOUS | MAP_POPULATE, -1, 0);
    if (p == MAP_FAILED) throw std::bad_alloc();
    return p;
  }
  // Over-map by one huge page and keep the 2 MB-aligned part: huge pages need the
  // alignment. Both trimmed ends are whole pages (length is page-rounded).
  const size_t mapped = length + kHugePage;
  void* raw = mmap(nullptr, mapped, PROT_READ | PROT_WRITE, MAP_PRIVATE | MAP_ANONYMOUS | MAP_NORESERVE, -1, 0);
  if (raw == MAP_FAILED) throw std::bad_alloc();
  const uintptr_t start = reinterpret_cast<uintptr_t>(raw);
  const uintptr_t aligned = (start + kHugePage - 1) & ~uintptr_t(kHugePage - 1);
  if (aligned > start) munmap(raw, aligned - start);
  const uintptr_t end = aligned + length, mappedEnd = start + mapped;
  if (mappedEnd > end) munmap(reinterpret_cast<void*>(end), mappedEnd - end);
  void* p = reinterpret_cast<void*>(aligned);
  // Advice only, refused where THP is off (then 4 KB pages fault in as written). Not
  // populated: where freed memory goes back to the host (this project's VMs), a
  // fresh page costs the same however it is faulted, and an emitter's block is
  // written only as far as its batches reach.
  madvise(p, length, MADV_HUGEPAGE);
  return p;
}

void unmapPhotonMemory(void* p, size_t bytes) noexcept {
  if (p) munmap(p, pageRounded(bytes));
}

void prefaultForWrite(void* p, size_t bytes) noexcept {
#ifdef MADV_POPULATE_WRITE  // glibc >= 2.35 headers (Debian 12 has 2.36); else a no-op
  const uintptr_t begin = (reinterpret_cast<uintptr_t>(p) + kPage - 1) & ~uintptr_t(kPage - 1);
  const uintptr_t end = (reinterpret_cast<uintptr_t>(p) + bytes) & ~uintptr_t(kPage - 1);
  if (end > begin) madvise(reinterpret_cast<void*>(begin), end - begin, MADV_POPULATE_WRITE);
#else
  (void)p;
  (void)bytes;
#endif
}

}  // namespace penumbra
