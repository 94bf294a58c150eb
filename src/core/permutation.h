// Element i of a pseudo-random permutation of [0, n), drawn from a seed without storing
// the permutation (Kensler 2013, "Correlated multi-jittered sampling"): pairs the strata
// of independent sample dimensions without correlating them.
#pragma once
#include <cstdint>

namespace penumbra {

// A hash that is a bijection on the smallest power of two holding n, walked until it
// lands inside [0, n) (cycle walking), then rotated by the seed: for a random seed every
// element is uniform on [0, n), so dimensions permuted by independent seeds stay unbiased.
inline uint32_t permutationElement(uint32_t i, uint32_t n, uint32_t seed) {
  uint32_t w = n - 1;  // all ones up to n - 1's top bit
  w |= w >> 1;
  w |= w >> 2;
  w |= w >> 4;
  w |= w >> 8;
  w |= w >> 16;
  do {
    i ^= seed;
    i *= 0xe170893du;
    i ^= seed >> 16;
    i ^= (i & w) >> 4;
    i ^= seed >> 8;
    i *= 0x0929eb3fu;
    i ^= seed >> 23;
    i ^= (i & w) >> 1;
    i *= 1u | seed >> 27;
    i *= 0x6935fa69u;
    i ^= (i & w) >> 11;
    i *= 0x74dcb303u;
    i ^= (i & w) >> 2;
    i *= 0x9e501cc3u;
    i ^= (i & w) >> 2;
    i *= 0xc860a3dfu;
    i &= w;
    i ^= i >> 5;
  } while (i >= n);
  return (i + seed % n) % n;
}

}  // namespace penumbra
