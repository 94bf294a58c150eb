// Shared fixtures for tests that build scenes by hand: materials, lights, rays,
// cameras and colour comparisons. Needs only core (and GoogleTest).
#pragma once
#include "core/ray_record.h"
#include "core/scene.h"
#include "geometry/ray.h"
#include <gtest/gtest.h>
#include <string>

namespace penumbra {

inline Material makeMaterial(const std::string& name, Color ambient, Color diffuse) {
  Material m;
  m.name = name;
  m.ambient = ambient;
  m.diffuse = diffuse;
  m.specular = Color(0.0f);
  return m;
}

inline Light directional(Vec3 travel, Color color, float intensity) {
  Light l;
  l.type = LightType::Directional;
  l.direction = glm::normalize(travel);
  l.color = color;
  l.intensity = intensity;
  return l;
}

inline Light point(Vec3 position, Color color, float intensity) {
  Light l;
  l.type = LightType::Point;
  l.position = position;
  l.color = color;
  l.intensity = intensity;
  return l;
}

inline Ray makeRay(Vec3 o, Vec3 d) {
  Ray r;
  r.origin = o;
  r.dir = glm::normalize(d);
  return r;
}

inline void expectColorNear(const Color& actual, const Color& expected, float tol, const std::string& what = "") {
  EXPECT_NEAR(actual.r, expected.r, tol) << what;
  EXPECT_NEAR(actual.g, expected.g, tol) << what;
  EXPECT_NEAR(actual.b, expected.b, tol) << what;
}

// Odd image sizes put the centre pixel's sample exactly on the optical axis.
inline Camera axisCamera(Vec3 position, Vec3 lookAt, float fov = 30.0f) {
  Camera c;
  c.position = position;
  c.lookAt = lookAt;
  c.fovY = fov;
  c.width = 65;
  c.height = 49;
  c.spp = 1;
  return c;
}

// The tree without its shadow rays: camera, reflection and refraction only.
inline RayTree withoutShadowRays(const RayTree& tree) {
  RayTree out;
  for (const RayRecord& r : tree) {
    if (r.kind != "shadow") out.push_back(r);
  }
  return out;
}

}  // namespace penumbra
