// One node of a pixel's ray tree, recorded by `--trace-pixel` for debugging
// (the report found its refraction bugs by logging the central pixels' rays).
#pragma once
#include "core/math.h"
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
};

using RayTree = std::vector<RayRecord>;

}  // namespace penumbra
