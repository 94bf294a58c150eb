// MapSlots: one slot per map kind with the kind's own photon type, visited in
// kAllMaps order, reached by a compile-time or a run-time kind.
#include "core/map_kind.h"
#include "core/photon.h"
#include <gtest/gtest.h>
#include <string>
#include <type_traits>
#include <vector>

namespace penumbra {
namespace {

template <class P>
using Records = std::vector<P>;
template <class P>
using Pointer = const P*;

static_assert(std::is_same_v<PhotonOf<MapKind::Shadow>, ShadowPhoton>);
static_assert(std::is_same_v<PhotonOf<MapKind::Indirect>, IndirectPhoton>);
static_assert(std::is_same_v<PhotonOf<MapKind::Global>, IndirectPhoton>);
static_assert(std::is_same_v<PhotonOf<MapKind::Caustic>, IndirectPhoton>);
static_assert(std::is_same_v<PhotonOf<MapKind::Volume>, VolumePhoton>);
static_assert(std::is_same_v<decltype(std::declval<MapSlots<Records>&>().get<MapKind::Shadow>()), Records<ShadowPhoton>&>);

TEST(MapSlots, EachKindHoldsItsOwnPhotonType) {
  MapSlots<Records> slots;
  slots.get<MapKind::Shadow>().resize(1);
  slots.get<MapKind::Indirect>().resize(2);
  slots.get<MapKind::Global>().resize(3);
  slots.get<MapKind::Caustic>().resize(4);
  slots.get<MapKind::Volume>().resize(5);
  std::vector<std::string> seen;
  std::vector<size_t> sizes, bytes;
  slots.forEach([&](MapKind k, const auto& records) {
    seen.push_back(mapName(k));
    sizes.push_back(records.size());
    bytes.push_back(sizeof(typename std::decay_t<decltype(records)>::value_type));
  });
  EXPECT_EQ(seen, (std::vector<std::string>{"shadow", "indirect", "global", "caustic", "volume"}));  // kAllMaps order
  EXPECT_EQ(sizes, (std::vector<size_t>{1, 2, 3, 4, 5}));
  EXPECT_EQ(bytes, (std::vector<size_t>{sizeof(ShadowPhoton), sizeof(IndirectPhoton), sizeof(IndirectPhoton),
                                        sizeof(IndirectPhoton), sizeof(VolumePhoton)}));
  // The surface light maps' run-time slot; Shadow and Volume hold other records.
  EXPECT_EQ(slots.light(MapKind::Volume), nullptr);
  EXPECT_EQ(slots.light(MapKind::Caustic)->size(), 4u);
}

TEST(MapSlots, KindIsACompileTimeConstantAndIndexesAPerMap) {
  const MapSlots<Records> slots;
  PerMap<size_t> photonBytes;
  slots.forEach([&](auto kind, const auto&) { photonBytes[kind] = sizeof(PhotonOf<decltype(kind)::value>); });
  EXPECT_EQ(photonBytes[MapKind::Shadow], sizeof(ShadowPhoton));
  EXPECT_EQ(photonBytes[MapKind::Caustic], sizeof(IndirectPhoton));
  size_t kinds = 0;
  forEachKind([&](auto kind) { kinds += sizeof(PhotonOf<decltype(kind)::value>) > 0 ? 1 : 0; });
  EXPECT_EQ(kinds, kMapKinds);
}

TEST(MapSlots, PointersStartNullAndWithReachesOneKind) {
  MapSlots<Pointer> maps;
  maps.forEach([](MapKind k, auto p) { EXPECT_EQ(p, nullptr) << mapName(k); });
  const IndirectPhoton photon{};
  maps.get<MapKind::Global>() = &photon;
  int calls = 0;
  maps.with(MapKind::Global, [&](MapKind k, auto p) {
    ++calls;
    EXPECT_EQ(k, MapKind::Global);
    EXPECT_EQ(static_cast<const void*>(p), &photon);
  });
  maps.with(MapKind::Caustic, [&](MapKind, auto p) { EXPECT_EQ(p, nullptr); });
  EXPECT_EQ(calls, 1);
}

}  // namespace
}  // namespace penumbra
