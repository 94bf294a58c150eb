// The photon maps by kind, and one value per kind: budgets, counts, rates and
// flags are a PerMap, so a new map is one more enumerator, not a field in every struct.
#pragma once
#include <array>
#include <cstddef>
#include <cstdint>
#include <tuple>
#include <type_traits>
#include <utility>

namespace penumbra {

// Shadow: the gate's shadow photons (both models); Indirect: the classic model's
// indirect map; Global and Caustic: the physical model's surface maps (Jensen's split);
// Volume: its photons scattered in participating media (scenes with a medium only).
enum class MapKind : uint8_t { Shadow, Indirect, Global, Caustic, Volume };
inline constexpr size_t kMapKinds = 5;
inline constexpr std::array<MapKind, kMapKinds> kAllMaps = {MapKind::Shadow, MapKind::Indirect, MapKind::Global,
                                                           MapKind::Caustic, MapKind::Volume};

// "shadow", "indirect", "global", "caustic", "volume": the photons.* keys and the stats' suffixes.
inline const char* mapName(MapKind k) {
  constexpr const char* kNames[kMapKinds] = {"shadow", "indirect", "global", "caustic", "volume"};
  return kNames[static_cast<size_t>(k)];
}

struct ShadowPhoton;
struct IndirectPhoton;
struct VolumePhoton;

// The photon record a map of kind K stores: the gate's shadow photons, the volume
// map's scattering events, or the surface maps' power-carrying photons.
template <MapKind K>
using PhotonOf = std::conditional_t<K == MapKind::Shadow, ShadowPhoton,
                                    std::conditional_t<K == MapKind::Volume, VolumePhoton, IndirectPhoton>>;

// A kind known at compile time; converts to MapKind, so it indexes a PerMap too.
template <MapKind K>
using MapKindTag = std::integral_constant<MapKind, K>;

// Calls f(MapKindTag<K>{}) for every kind, in kAllMaps order.
template <class F>
void forEachKind(F&& f) {
  static_assert(kAllMaps[0] == MapKind(0) && kAllMaps[1] == MapKind(1) && kAllMaps[2] == MapKind(2) &&
                    kAllMaps[3] == MapKind(3) && kAllMaps[4] == MapKind(4) && kMapKinds == 5,
                "kAllMaps lists the kinds in enum order");
  [&f](auto... i) { (f(MapKindTag<kAllMaps[decltype(i)::value]>{}), ...); }(
      std::integral_constant<size_t, 0>{}, std::integral_constant<size_t, 1>{}, std::integral_constant<size_t, 2>{},
      std::integral_constant<size_t, 3>{}, std::integral_constant<size_t, 4>{});
}

// One Slot<PhotonOf<K>> per kind (a map, its photons, a pointer to it): the
// heterogeneous PerMap, with no unused slot of the wrong photon type.
template <template <class> class Slot>
class MapSlots {
  template <size_t... I>
  static std::tuple<Slot<PhotonOf<kAllMaps[I]>>...> slotsOf(std::index_sequence<I...>);

 public:
  template <MapKind K>
  Slot<PhotonOf<K>>& get() { return std::get<static_cast<size_t>(K)>(slots_); }
  template <MapKind K>
  const Slot<PhotonOf<K>>& get() const { return std::get<static_cast<size_t>(K)>(slots_); }

  // f(kind, slot) for every kind in kAllMaps order; `kind` is a MapKindTag, so f
  // may read it as a MapKind or as a compile-time constant.
  template <class F>
  void forEach(F&& f) {
    forEachKind([&](auto kind) { f(kind, get<decltype(kind)::value>()); });
  }
  template <class F>
  void forEach(F&& f) const {
    forEachKind([&](auto kind) { f(kind, get<decltype(kind)::value>()); });
  }
  // f(kind, slot) for the one kind `k` chosen at run time.
  template <class F>
  void with(MapKind k, F&& f) {
    forEach([&](auto kind, auto& slot) { if (kind == k) f(kind, slot); });
  }
  template <class F>
  void with(MapKind k, F&& f) const {
    forEach([&](auto kind, const auto& slot) { if (kind == k) f(kind, slot); });
  }
  // The slot of a surface light map (Indirect, Global, Caustic) chosen at run time;
  // null for Shadow and Volume, whose records differ.
  Slot<IndirectPhoton>* light(MapKind k) {
    Slot<IndirectPhoton>* out = nullptr;
    forEach([&](auto kind, auto& slot) {
      if constexpr (std::is_same_v<PhotonOf<decltype(kind)::value>, IndirectPhoton>) {
        if (kind == k) out = &slot;
      }
    });
    return out;
  }
  const Slot<IndirectPhoton>* light(MapKind k) const { return const_cast<MapSlots*>(this)->light(k); }

 private:
  decltype(slotsOf(std::make_index_sequence<kMapKinds>{})) slots_;
};

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
