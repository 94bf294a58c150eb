// The list of light types and what each answers by plain data (its traits): the one
// place a new light type is named. Behaviour lives in light_sample.h's dispatchers.
#pragma once
#include <cstddef>
#include <cstdint>

namespace penumbra {

// Point and directional lights are deltas; quad, sphere and mesh lights are area
// emitters, sampled light_samples times per shading point and visible to rays. A mesh
// light is the triangles of every mesh whose material has an emission. An environment
// (at most one, always the last light) lights from every direction at infinity and is
// what rays leaving the scene see (core/environment.h).
enum class LightType : uint8_t { Point, Directional, Quad, Sphere, Mesh, Environment };

// Where a light's emission comes from, as pbrt names it: a point or a direction
// (deltas, one sample per shading point), a surface, or every direction at infinity.
enum class LightSupport : uint8_t { Position, Direction, Area, Infinite };

// The strata the shadow gate votes on separately (core/light_strata.h): one; a 4x4 grid
// of the sample's own (u1, u2), each cell a region of the light seen from its front; or
// 4x4 equal-area cells of the surface where a sample lands.
enum class StrataKind : uint8_t { One, Parametric, Surface };

struct LightTraits {
  LightSupport support;
  StrataKind strata;
};

inline constexpr LightTraits kLightTraits[] = {
    /* Point */ {LightSupport::Position, StrataKind::One},
    /* Directional */ {LightSupport::Direction, StrataKind::One},
    /* Quad */ {LightSupport::Area, StrataKind::Parametric},
    /* Sphere */ {LightSupport::Area, StrataKind::Surface},
    /* Mesh: a triangle and its side come from one number, so (u, v) cells are not regions */
    {LightSupport::Area, StrataKind::One},
    /* Environment */ {LightSupport::Infinite, StrataKind::One},
};

constexpr const LightTraits& lightTraits(LightType type) { return kLightTraits[static_cast<size_t>(type)]; }

constexpr bool isDelta(LightType type) {
  return lightTraits(type).support == LightSupport::Position || lightTraits(type).support == LightSupport::Direction;
}

}  // namespace penumbra
