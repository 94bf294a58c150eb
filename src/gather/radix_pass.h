// One pass of a deterministic, stable, parallel counting sort: the step both the photon
// maps' storage order (morton.cpp) and the lookup cache's cell order are built from.
#pragma once
#include <tbb/parallel_for.h>
#include <algorithm>
#include <cassert>
#include <cstddef>
#include <cstdint>
#include <vector>

namespace penumbra {

// Records per chunk: a chunk counts and scatters its records on one thread, and the
// chunk count depends only on the record count, so the order does not depend on threads.
constexpr size_t kRadixChunk = size_t(1) << 16;
// 2048 buckets per pass: their write heads stay in cache.
constexpr int kMaxRadixDigitBits = 11;

// Records [0, n) of `src` (anything with forRange(begin, end, f(i, record)) in sequence
// order), each to place(at, i, record) where `at` is its rank by digitOf(i) (< 2^digitBits),
// ties in sequence order. Returns where each digit's records start, and n at the end.
// Ranks are 32-bit, as photon indices are (checkIndexable): n < 2^32.
template <class Source, class DigitOf, class Place>
std::vector<size_t> radixScatter(const Source& src, size_t n, int digitBits, DigitOf&& digitOf, Place&& place) {
  assert(n <= UINT32_MAX);
  const size_t buckets = size_t(1) << digitBits;
  const size_t chunks = (n + kRadixChunk - 1) / kRadixChunk;
  std::vector<uint32_t> head(chunks * buckets, 0);
  tbb::parallel_for(size_t(0), chunks, [&](size_t c) {
    uint32_t* h = &head[c * buckets];
    for (size_t i = c * kRadixChunk, e = std::min(n, i + kRadixChunk); i < e; ++i) ++h[digitOf(i)];
  });
  // Bucket-major, chunk-minor: chunk c's records of a digit follow those of chunks < c.
  std::vector<size_t> starts(buckets + 1, n);
  uint32_t running = 0;
  for (size_t d = 0; d < buckets; ++d) {
    starts[d] = running;
    for (size_t c = 0; c < chunks; ++c) {
      const uint32_t x = head[c * buckets + d];
      head[c * buckets + d] = running;
      running += x;
    }
  }
  tbb::parallel_for(size_t(0), chunks, [&](size_t c) {
    uint32_t* h = &head[c * buckets];
    src.forRange(c * kRadixChunk, std::min(n, (c + 1) * kRadixChunk),
                 [&](size_t i, const auto& record) { place(size_t(h[digitOf(i)]++), i, record); });
  });
  return starts;
}

// A plain array as a radixScatter source.
template <class T>
struct ArraySource {
  const T* data;
  template <class F>
  void forRange(size_t begin, size_t end, F&& f) const {
    for (size_t i = begin; i < end; ++i) f(i, data[i]);
  }
};

}  // namespace penumbra
