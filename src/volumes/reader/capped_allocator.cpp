// The reader process's global operator new and delete under a cap (capped_allocator.h).
// Every non-aligned form is replaced, so each block is freed by the free that matches its
// malloc; the aligned forms stay the runtime's, pairs of their own.
#include "volumes/reader/capped_allocator.h"

#include <malloc.h>

#include <algorithm>
#include <atomic>
#include <cstdlib>
#include <new>

// ThreadSanitizer's runtime defines these operators itself (not replaceably), so a TSan
// build's reader runs without the cap; its deadline and output cap still hold.
#if defined(__SANITIZE_THREAD__)
#define PENUMBRA_TSAN 1
#elif defined(__has_feature)
#if __has_feature(thread_sanitizer)
#define PENUMBRA_TSAN 1
#endif
#endif

#ifdef PENUMBRA_TSAN
namespace penumbra::volumes {
void setAllocationCap(uint64_t) {}
}  // namespace penumbra::volumes
#else

namespace penumbra::volumes {
namespace {

std::atomic<uint64_t> gCap{0}, gHeld{0};

void* allocate(std::size_t n) noexcept {
  // Refused before malloc when the request alone passes the cap (nothing is mapped).
  const uint64_t limit = gCap.load(std::memory_order_relaxed);
  if (limit != 0 && n > limit - std::min(limit, gHeld.load(std::memory_order_relaxed))) return nullptr;
  void* p = std::malloc(n != 0 ? n : 1);
  if (!p) return nullptr;
  const uint64_t size = ::malloc_usable_size(p);
  const uint64_t held = gHeld.fetch_add(size, std::memory_order_relaxed) + size;
  const uint64_t cap = gCap.load(std::memory_order_relaxed);
  if (cap != 0 && held > cap) {
    gHeld.fetch_sub(size, std::memory_order_relaxed);
    std::free(p);
    return nullptr;
  }
  return p;
}

void release(void* p) noexcept {
  if (!p) return;
  gHeld.fetch_sub(::malloc_usable_size(p), std::memory_order_relaxed);
  std::free(p);
}

void* allocateOrThrow(std::size_t n) {
  if (void* p = allocate(n)) return p;
  throw std::bad_alloc();
}

}  // namespace

void setAllocationCap(uint64_t bytes) { gCap.store(bytes, std::memory_order_relaxed); }

}  // namespace penumbra::volumes

using penumbra::volumes::allocate;
using penumbra::volumes::allocateOrThrow;
using penumbra::volumes::release;

void* operator new(std::size_t n) { return allocateOrThrow(n); }
void* operator new[](std::size_t n) { return allocateOrThrow(n); }
void* operator new(std::size_t n, const std::nothrow_t&) noexcept { return allocate(n); }
void* operator new[](std::size_t n, const std::nothrow_t&) noexcept { return allocate(n); }
void operator delete(void* p) noexcept { release(p); }
void operator delete[](void* p) noexcept { release(p); }
void operator delete(void* p, std::size_t) noexcept { release(p); }
void operator delete[](void* p, std::size_t) noexcept { release(p); }
void operator delete(void* p, const std::nothrow_t&) noexcept { release(p); }
void operator delete[](void* p, const std::nothrow_t&) noexcept { release(p); }

#endif  // PENUMBRA_TSAN
