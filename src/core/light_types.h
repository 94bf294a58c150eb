// The list of light types: each type's traits (what it answers by plain data) and the
// struct of static functions holding its code (core/lights/), joined by one type list
// that dispatchLight turns into a switch. The one place a new light type is named.
#pragma once
#include "core/math.h"
#include <array>
#include <cstddef>
#include <cstdint>
#include <tuple>
#include <utility>

namespace penumbra {

// Point, spot and directional lights are deltas; quad, disk, sphere and mesh lights are area
// emitters, sampled light_samples times per shading point and visible to rays. A mesh
// light is the triangles of every mesh whose material has an emission. An environment
// (at most one, always the last light) lights from every direction at infinity and is
// what rays leaving the scene see (core/lights/environment_map.h).
// A new type: an enumerator here, its header and its AllLights entry below.
enum class LightType : uint8_t { Point, Directional, Quad, Sphere, Mesh, Environment, Spot, Disk };

// Where a light's emission comes from, as pbrt names it: a point or a direction
// (deltas, one sample per shading point), a surface, or every direction at infinity.
enum class LightSupport : uint8_t { Position, Direction, Area, Infinite };

// The strata the shadow gate votes on separately (core/light_strata.h): one; a 4x4 grid
// of the sample's own (u1, u2), each cell a region of the light seen from its front; or
// 4x4 equal-area cells of the surface where a sample lands.
enum class StrataKind : uint8_t { One, Parametric, Surface };

// How the physical model's caustic photons aim at the specular targets (emit/caustic_aim.h):
// not at all; cones from the light's position; discs along its direction; from a start
// on its surface; from a start on a cap of the sphere that faces a target.
enum class AimKind : uint8_t { None, Cone, Disc, Surface, SphereCaps };

// What decides a shadow ray: anything on the segment short of the sample point; or
// the first surface the ray meets, which lets it through when that is the emitter
// itself (a sphere: near its silhouette a lifted ray can enter it before the sample).
enum class ShadowTest : uint8_t { Segment, FirstHitIsEmitter };

// How the tracers light a point by it: gated light samples (directFromLight), or
// multiple importance sampling of the light and the BSDF (directFromEnvironment).
enum class DirectSampling : uint8_t { Gated, EnvironmentMis };

// What a light type answers without running code: read by the stages in loops.
struct LightTraits {
  LightSupport support;
  StrataKind strata;
  AimKind aim;
  ShadowTest shadowTest;
  DirectSampling direct;
  // It emits shadow photons (so the gate can answer for it) and classic photons.
  bool emitsShadowPhotons;
  // It emits the physical model's photons, so on its own it keeps those maps on. A
  // directional light does not, though it emits physical photons when another light
  // keeps them on (as the renderer has always done).
  bool opensPhysicalMaps;
  // The resource estimate's cost model: the gate's verdicts spare most of its shadow
  // rays (not a mesh light's: a large emitter near what it lights leaves most points mixed).
  bool gateAvoidsRays;
  // Its "type" in the scene file's "lights" (null: it comes from elsewhere, a mesh's
  // emission or the environment).
  const char* name;
  // Its total power as the float checks' messages spell it.
  const char* powerFormula;
};

// The power formula of a Lambertian area emitter (pi A L), as the messages spell it.
inline constexpr const char* kLambertianPower = "pi x area x color x radiance";

struct Light;
struct LightSampler;
struct LightIncidence;
struct PhotonRay;
struct SceneSphere;
struct EmitterShape;
struct TriangleMesh;

// The answers a type leaves out (defined in light_sample.cpp). Each type is a struct
// of static functions deriving from this; the dispatchers in light_sample.cpp call
// T::f, so a type overrides a default by declaring its own f.
struct LightDefaults {
  // Per shading point, before its samples: nothing to set up.
  static void prepare(const Light& light, const Vec3& p, LightSampler& s);
  // No closed form: sample.
  static bool irradiance(const LightSampler& s, const Vec3& n, const Vec3& ng, Color& E);
  static float area(const Light& light);  // 0: not an area light
  // A Lambertian emitter's flux: pi A L.
  static Color power(const Light& light, const SceneSphere& bounds);
  // Its share of the classic photon budget, in a point light's intensity units: pi A L / (4 pi).
  static float classicWeight(const Light& light);
  // Each of `count` classic photons carries power / count.
  static Color classicPower(const Light& light, const SceneSphere& bounds, float count);
  // Uniform numbers a photon's start reads (photon's u1..u4): all four.
  static int startNumbers(const Light& light);
  // An area (or infinite) light's photon leaves from its drawn point lifted off the
  // surface along its normal, so its first ray misses the emitter.
  static Vec3 photonOrigin(const Light& light, const PhotonRay& r, const SceneSphere& bounds);
  // The surface that joins the scene as an emitting object: none (a delta light; a mesh
  // light's triangles are in the scene already; the environment is what rays leaving see).
  static EmitterShape emitter(const Light& light);
  // Entries one sample searches (a binary search's table); 0: it draws without one.
  static size_t sampleTable(const Light& light);
};

}  // namespace penumbra

// One header per type; each declares only, with the forward declarations above.
#include "core/lights/point_light.h"
#include "core/lights/directional_light.h"
#include "core/lights/quad_light.h"
#include "core/lights/sphere_light.h"
#include "core/lights/mesh_light.h"
#include "core/lights/environment_light.h"
#include "core/lights/spot_light.h"
#include "core/lights/disk_light.h"

namespace penumbra {

template <class... Ts>
struct LightTypeList {};
// In the enum's order: the i-th type handles LightType value i.
using AllLights =
    LightTypeList<PointLight, DirectionalLight, QuadLight, SphereLight, MeshLight, EnvironmentLight, SpotLight,
                  DiskLight>;

namespace light_list {
template <class... Ts, size_t... I>
constexpr bool inEnumOrder(LightTypeList<Ts...>, std::index_sequence<I...>) {
  return ((Ts::kType == static_cast<LightType>(I)) && ...);
}
template <class... Ts>
constexpr std::array<LightTraits, sizeof...(Ts)> traitsOf(LightTypeList<Ts...>) {
  return {Ts::kTraits...};
}
template <class... Ts>
constexpr size_t countOf(LightTypeList<Ts...>) {
  return sizeof...(Ts);
}

// pbrt-v4's TaggedPointer::Dispatch: a switch over the list, so a hot loop pays a
// jump, never a virtual call.
template <class F, class... Ts>
decltype(auto) dispatch(LightType type, F&& f, LightTypeList<Ts...>) {
  constexpr size_t n = sizeof...(Ts);
  static_assert(n <= 16, "dispatch switches over at most 16 types: add cases");
  using List = std::tuple<Ts...>;
  // Cases past the list are discarded at compile time (if constexpr), not dispatched.
#define PENUMBRA_LIGHT_CASE(i) \
  case i:                      \
    if constexpr (i < n) return f(std::tuple_element_t<(i < n ? i : 0), List>{}); \
    break;
  switch (static_cast<size_t>(type)) {
    PENUMBRA_LIGHT_CASE(0) PENUMBRA_LIGHT_CASE(1) PENUMBRA_LIGHT_CASE(2) PENUMBRA_LIGHT_CASE(3)
    PENUMBRA_LIGHT_CASE(4) PENUMBRA_LIGHT_CASE(5) PENUMBRA_LIGHT_CASE(6) PENUMBRA_LIGHT_CASE(7)
    PENUMBRA_LIGHT_CASE(8) PENUMBRA_LIGHT_CASE(9) PENUMBRA_LIGHT_CASE(10) PENUMBRA_LIGHT_CASE(11)
    PENUMBRA_LIGHT_CASE(12) PENUMBRA_LIGHT_CASE(13) PENUMBRA_LIGHT_CASE(14) PENUMBRA_LIGHT_CASE(15)
  }
#undef PENUMBRA_LIGHT_CASE
  __builtin_unreachable();  // a LightType value with no entry in AllLights
}
}  // namespace light_list

inline constexpr size_t kLightTypes = light_list::countOf(AllLights{});
static_assert(light_list::inEnumOrder(AllLights{}, std::make_index_sequence<kLightTypes>{}),
              "AllLights lists the types in LightType's order");
inline constexpr auto kLightTraits = light_list::traitsOf(AllLights{});

constexpr const LightTraits& lightTraits(LightType type) { return kLightTraits[static_cast<size_t>(type)]; }

constexpr bool isDelta(LightType type) {
  return lightTraits(type).support == LightSupport::Position || lightTraits(type).support == LightSupport::Direction;
}

// Calls f(T{}) with the struct T of `type` (core/lights/), e.g.
// dispatchLight(light.type, [&](auto t) { return decltype(t)::area(light); }).
template <class F>
decltype(auto) dispatchLight(LightType type, F&& f) {
  return light_list::dispatch(type, std::forward<F>(f), AllLights{});
}

}  // namespace penumbra
