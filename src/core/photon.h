// Photon records as stored in the maps. Compact on purpose: 5M photons per map,
// the normal/direction are octahedral-encoded into 32 bits each and an indirect
// photon's power is a 32-bit shared-exponent colour.
#pragma once
#include "core/math.h"
#include "core/mapped_memory.h"
#include <cstdint>
#include <cstring>
#include <new>
#include <type_traits>
#include <utility>
#include <vector>

namespace penumbra {

// Octahedral unit-vector encoding (Cigolle et al. 2014), 16 bits per axis:
// worst-case angular error ~0.005 degrees, plenty for a "same side" test.
// Decoding is inline: the gate's cells decode every shadow photon's normal.
uint32_t encodeOctahedral(const Vec3& unit);
inline Vec2 octahedralSigns(Vec2 v) { return {v.x >= 0.0f ? 1.0f : -1.0f, v.y >= 0.0f ? 1.0f : -1.0f}; }
inline Vec3 decodeOctahedral(uint32_t code) {
  Vec2 p(static_cast<float>(code & 0xFFFFu) / 65535.0f * 2.0f - 1.0f,
         static_cast<float>(code >> 16) / 65535.0f * 2.0f - 1.0f);
  Vec3 n(p.x, p.y, 1.0f - std::abs(p.x) - std::abs(p.y));
  if (n.z < 0.0f) {
    Vec2 xy = (1.0f - glm::abs(Vec2(n.y, n.x))) * octahedralSigns(p);
    n.x = xy.x;
    n.y = xy.y;
  }
  return glm::normalize(n);
}

// A gather's normal filter: whether a photon's stored normal faces within
// acos(minCos) of the query's n. Photons on the query's own plane carry n's own code,
// whose answer is found once instead of decoding each of them (equal codes decode
// equal, so the answer is the same).
class NormalFilter {
 public:
  NormalFilter(const Vec3& n, float minCos);
  bool passes(uint32_t code) const { return code == ownCode_ ? ownPasses_ : cosineOf(code) > minCos_; }
  float cosineOf(uint32_t code) const { return glm::dot(decodeOctahedral(code), n_); }
  // Whether `code` is the query's own and passes: no decode needed.
  bool passesAsOwn(uint32_t code) const { return code == ownCode_ && ownPasses_; }

 private:
  Vec3 n_;
  float minCos_;
  uint32_t ownCode_ = 0;
  bool ownPasses_ = false;
};

// A photon's power in 32 bits: Ward's RGBE shared-exponent colour (Graphics Gems II,
// "Real pixels"). Three 8-bit mantissas share the largest channel's exponent, so it
// covers the float range without a per-map scale. Encoding rounds each channel to
// nearest (the largest rounding up to 256 bumps the exponent), so decoding adds no
// +0.5: every channel comes back within 2^-8 (0.39%) of the LARGEST channel (a weak
// channel beside a strong one keeps only that absolute precision). Zero, negative
// and non-finite channels, and colours whose largest channel is below 2^-100, store
// as 0; a largest channel of 2^127 or more saturates at 255 x 2^119 (~1.7e38).
// Byte layout: r | g << 8 | b << 16 | exponent << 24; bits == 0 is exactly black.
struct PackedPower {
  uint32_t bits = 0;
  PackedPower() = default;
  PackedPower(const Color& c);  // implicit on purpose: records are built from colours
  Color color() const {
    const uint32_t e = bits >> 24;
    if (e == 0) return Color(0.0f);
    // The scale 2^(e - 136) = 2^(e - 128 - 8), built from its float bits: e >= 29
    // for every stored colour, so the biased exponent e - 9 is a normal float's.
    const uint32_t scaleBits = (e - 9u) << 23;
    float scale;
    std::memcpy(&scale, &scaleBits, sizeof scale);
    return Color(static_cast<float>(bits & 0xFFu), static_cast<float>((bits >> 8) & 0xFFu),
                 static_cast<float>((bits >> 16) & 0xFFu)) * scale;
  }
  bool operator==(const PackedPower& o) const { return bits == o.bits; }
  bool operator!=(const PackedPower& o) const { return bits != o.bits; }
};

// Photon arrays reach hundreds of MB. std::vector(n) and resize(n) would zero every
// element on one thread before the parallel pass that overwrites them all (a serial
// first touch of every page): this allocator leaves elements uninitialised instead,
// so the parallel writer touches the pages first. Only for trivially copyable
// records, each of which is written before it is read. Large arrays are mapped from
// the kernel (core/mapped_memory.h): huge pages from 2 MB on.
template <class T>
struct UninitialisedAllocator : std::allocator<T> {
  static_assert(std::is_trivially_copyable_v<T>, "photon records are plain bytes");
  template <class U>
  struct rebind {
    using other = UninitialisedAllocator<U>;
  };
  UninitialisedAllocator() = default;
  template <class U>
  UninitialisedAllocator(const UninitialisedAllocator<U>&) noexcept {}
  template <class U>
  void construct(U*) noexcept {}  // resize(n), vector(n): the caller writes every element
  T* allocate(size_t n) {
    if (n * sizeof(T) >= kMappedMinBytes) return static_cast<T*>(mapPhotonMemory(n * sizeof(T)));
    return std::allocator<T>::allocate(n);
  }
  void deallocate(T* p, size_t n) noexcept {
    if (n * sizeof(T) >= kMappedMinBytes) return unmapPhotonMemory(p, n * sizeof(T));
    std::allocator<T>::deallocate(p, n);
  }
  template <class U, class... Args>
  void construct(U* p, Args&&... args) {
    ::new (static_cast<void*>(p)) U(std::forward<Args>(args)...);
  }
};
template <class T>
using PhotonArray = std::vector<T, UninitialisedAllocator<T>>;

// What lies between a shadow photon and its light. Behind glass alone the light
// arrives tinted, which only a shadow ray can measure.
enum ShadowKind : uint8_t { kDirect = 0, kShadowOpaque = 1, kShadowGlass = 2 };

// A hit along a shadow photon's line: the first is direct, every later one a shadow.
// backSide: the line met the surface's back (against its winding's normal), as a line
// leaving a closed object does; only points seen on that side read its vote. Bit-fields
// take no default member initialiser before C++20: brace-initialise ShadowPhoton{}.
struct ShadowPhoton {
  Vec3 position;
  uint32_t normal;  // octahedral geometric normal, flipped to face where the photon came from
  uint16_t light;   // index into Scene::lights
  uint8_t shadow;   // a ShadowKind: direct, behind something opaque, or behind glass only
  uint8_t stratum : 7;   // which stratum of its light it left from (core/light_strata.h)
  uint8_t backSide : 1;  // met the surface from behind
};

// An indirect-map photon: stored at every surface hit of a bouncing path.
// 24 bytes: the map's budget is <= 32 B per stored photon including the KD-tree
// index, and a float Color alone would take 12 of them. The power is packed (4 B);
// the estimators average >= 50 photons, so the <= 0.4% rounding of each photon's
// power is far below their noise (~1/sqrt(k), 14% at k = 50). The bound is relative
// to the photon's largest channel, and photons of one colour round alike, so a weak
// channel beside a strong one can be biased by up to 2^-8 of the strong one, which is
// large relative to the weak channel but small in the pixel. Read the power once per photon with
// power.color(); emitters compute in float and pack only at the store.
struct IndirectPhoton {
  Vec3 position;
  PackedPower power;   // shared-exponent RGB, within 2^-8 of the largest channel
  uint32_t direction;  // octahedral, incoming direction of travel
  uint32_t normal;     // octahedral geometric normal, flipped to face where the photon came from
};
static_assert(sizeof(IndirectPhoton) == 24, "IndirectPhoton: 12 B position + 3 x 4 B codes");

// A volume-map photon: stored at a scattering event in a medium, with the power that
// arrives there and its direction of travel. It keeps its medium instead of a normal,
// so a beam in one medium never reads the photons of another across their boundary.
struct VolumePhoton {
  Vec3 position;
  PackedPower power;   // shared-exponent RGB, as IndirectPhoton's
  uint32_t direction;  // octahedral, arriving direction of travel
  int32_t medium;      // index into Scene::media
};
static_assert(sizeof(VolumePhoton) == 24, "VolumePhoton: 12 B position + 3 x 4 B fields");

}  // namespace penumbra
