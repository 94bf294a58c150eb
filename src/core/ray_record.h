// One node of a pixel's ray tree, recorded by `--trace-pixel` for debugging
// (the report found its refraction bugs by logging the central pixels' rays).
#pragma once
#include "core/math.h"
#include <algorithm>
#include <cmath>
#include <string>
#include <vector>

namespace penumbra {

struct RayRecord {
  std::string kind;  // camera, reflection, refraction, shadow
  int parent = -1;   // index of the ray that spawned it, -1 for camera rays
  int depth = 0;
  Vec3 origin{0.0f}, dir{0.0f};
  bool hit = false;  // shadow rays: true when blocked or filtered before the light
  float t = 0.0f;
  Vec3 position{0.0f};
  std::string material;  // material hit, empty on a miss
  bool entering = false;  // refraction: entering the surface (true) or leaving
  Color weight{1.0f};     // path weight carried into this ray
  Color contribution{0.0f};  // weight x radiance returned along this ray (shadow rays: transmittance)
  std::string note;          // e.g. "total internal reflection", gate verdict
  // The surface as shaded (hits the integrator shaded; a light's own surface is not).
  bool shaded = false;
  bool hasUv = false;                // the material reads textures: `uv` is the mesh's own
  Vec2 uv{0.0f};
  Vec3 geometricNormal{0.0f};        // all three face the ray
  Vec3 interpolatedNormal{0.0f};     // the vertex normals' blend, before any normal map
  Vec3 shadingNormal{0.0f};          // what the BSDF used
  Color baseColor{0.0f};             // base (diffuse) colour after texture and vertex colour
  bool metalRough = false;           // a glTF metallic-roughness material: the two below apply
  float metallic = 0.0f, roughness = 0.0f;  // after the metallic-roughness map
};

using RayTree = std::vector<RayRecord>;

// How far a normal map tilts the shading normal from the interpolated one, in degrees
// (0 without a map).
inline float normalTiltDegrees(const RayRecord& r) {
  const float c = glm::dot(glm::normalize(r.interpolatedNormal), glm::normalize(r.shadingNormal));
  return glm::degrees(std::acos(std::clamp(c, -1.0f, 1.0f)));
}

}  // namespace penumbra
