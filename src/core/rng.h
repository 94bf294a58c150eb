// Counter-based random numbers. Every stream is keyed by *what* it samples
// (seed, pixel, sample or seed, batch), never by which thread runs it, so the
// image is the same bytes for any thread count.
#pragma once
#include <cstdint>

namespace penumbra {

// SplitMix64 finaliser: a strong 64-bit mix, used to turn keys into seeds.
constexpr uint64_t mix64(uint64_t z) {
  z += 0x9E3779B97F4A7C15ull;
  z = (z ^ (z >> 30)) * 0xBF58476D1CE4E5B9ull;
  z = (z ^ (z >> 27)) * 0x94D049BB133111EBull;
  return z ^ (z >> 31);
}
constexpr uint64_t hashKey(uint64_t a, uint64_t b) { return mix64(a ^ mix64(b)); }
constexpr uint64_t hashKey(uint64_t a, uint64_t b, uint64_t c) { return hashKey(hashKey(a, b), c); }

// PCG32 (O'Neill 2014): small state, good statistics, cheap to create per pixel.
class Rng {
 public:
  explicit Rng(uint64_t key, uint64_t stream = 0)
      : state_(0), inc_((stream << 1u) | 1u) {
    nextU32();
    state_ += mix64(key);
    nextU32();
  }
  uint32_t nextU32() {
    uint64_t old = state_;
    state_ = old * 6364136223846793005ull + inc_;
    uint32_t xorshifted = static_cast<uint32_t>(((old >> 18u) ^ old) >> 27u);
    uint32_t rot = static_cast<uint32_t>(old >> 59u);
    return (xorshifted >> rot) | (xorshifted << ((~rot + 1u) & 31));
  }
  // Uniform in [0, 1): 24 random mantissa bits, so never rounds up to 1.
  float uniform() { return static_cast<float>(nextU32() >> 8) * 0x1p-24f; }

 private:
  uint64_t state_;
  uint64_t inc_;
};

}  // namespace penumbra
