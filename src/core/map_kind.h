// The photon maps by kind, and one value per kind: budgets, counts, rates and
// flags are a PerMap, so a new map is one more enumerator, not a field in every struct.
#pragma once
#include <array>
#include <cstddef>
#include <cstdint>

namespace penumbra {

// Shadow: the gate's shadow photons (both models); Indirect: the classic model's
// indirect map; Global and Caustic: the physical model's maps (Jensen's split).
enum class MapKind : uint8_t { Shadow, Indirect, Global, Caustic };
inline constexpr size_t kMapKinds = 4;
inline constexpr std::array<MapKind, kMapKinds> kAllMaps = {MapKind::Shadow, MapKind::Indirect, MapKind::Global,
                                                           MapKind::Caustic};

// "shadow", "indirect", "global", "caustic": the photons.* keys and the stats' suffixes.
inline const char* mapName(MapKind k) {
  constexpr const char* kNames[kMapKinds] = {"shadow", "indirect", "global", "caustic"};
  return kNames[static_cast<size_t>(k)];
}

template <class T>
struct PerMap {
  std::array<T, kMapKinds> values{};
  T& operator[](MapKind k) { return values[static_cast<size_t>(k)]; }
  const T& operator[](MapKind k) const { return values[static_cast<size_t>(k)]; }
  bool operator==(const PerMap& o) const { return values == o.values; }
  bool operator!=(const PerMap& o) const { return values != o.values; }
};

// Photons per map: a budget, or a count emitted or stored.
struct MapCounts : PerMap<uint64_t> {
  uint64_t total() const {
    uint64_t n = 0;
    for (uint64_t v : values) n += v;
    return n;
  }
  void maxWith(const MapCounts& o) {
    for (size_t i = 0; i < kMapKinds; ++i) values[i] = values[i] > o.values[i] ? values[i] : o.values[i];
  }
  MapCounts& operator+=(const MapCounts& o) {
    for (size_t i = 0; i < kMapKinds; ++i) values[i] += o.values[i];
    return *this;
  }
};

}  // namespace penumbra
