// The tracer's ray and its deliberately small hit record: only what Embree
// returns. It is expanded into a full SurfaceRecord only at shading time.
#pragma once
#include "core/math.h"
#include <cstdint>

namespace penumbra {

struct Ray {
  Vec3 origin{0.0f};
  Vec3 dir{0.0f, 0.0f, -1.0f};  // unit length
  float tMin = 0.0f;
  float tMax = kInf;
};

constexpr uint32_t kInvalidId = ~0u;

struct Hit {
  float t = kInf;
  float u = 0.0f, v = 0.0f;  // Embree barycentrics (triangles); unused for spheres
  uint32_t geomId = kInvalidId;
  uint32_t primId = kInvalidId;
  bool valid() const { return geomId != kInvalidId; }
};

}  // namespace penumbra
