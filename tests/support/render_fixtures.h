// Shared fixtures for the tracer tests: hand-built materials, lights, cameras
// and a Rig that renders a Scene without photon maps.
#pragma once
#include "trace/camera.h"
#include "trace/render.h"
#include "trace/shading.h"
#include "trace/trace_scene.h"
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

// Everything a render needs, built from a Scene owned by the caller.
struct Rig {
  explicit Rig(const Scene& s) : scene(s), tracer(s), ctx{s, tracer} {
    ctx.hasGlass = sceneHasGlass(s);
    ctx.pixelSpread = CameraRays(s.camera).pixelSpread();
  }
  Color shade(const Ray& ray, RayTree* tree = nullptr) const {
    ThreadState ts;
    ts.recorder = tree;
    return traceRay(ctx, ray, 0, Color(1.0f), 0.0f, RayKind::Camera, -1, ts);
  }
  Image render(Aov aov = Aov::Beauty) const {
    RenderOptions options;
    options.aov = aov;
    RayCounts counts;
    return renderImage(ctx, options, counts);
  }
  const Scene& scene;
  TraceScene tracer;
  ShadingContext ctx;
};

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
