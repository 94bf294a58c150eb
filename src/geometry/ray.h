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

// Embree asserts (and aborts the process) on a ray outside its domain: a coordinate or
// direction component beyond +-1.844e18 or NaN, a negative or NaN tnear, a NaN tfar. A
// NaN born upstream (an overflowed Fresnel term, say) must cost one pixel, not the run.
inline bool embreeAccepts(const Ray& r) {
  constexpr float kLarge = 1.844e18f;
  const Vec3 o = glm::abs(r.origin), d = glm::abs(r.dir);
  return maxComponent(glm::max(o, d)) <= kLarge && !std::isnan(o.x + o.y + o.z + d.x + d.y + d.z) &&
         r.tMin >= 0.0f && r.tMin <= kInf && !std::isnan(r.tMax);
}

}  // namespace penumbra
