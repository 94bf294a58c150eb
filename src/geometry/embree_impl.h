// Private to src/geometry: the Embree side of TraceScene. Only the geometry .cpp
// files include this header (and with it <embree3/rtcore.h>); the rest of the
// renderer sees TraceScene through trace_scene.h without any Embree type.
#pragma once
#include "core/alpha_mask.h"
#include "core/scene.h"
#include "geometry/trace_scene.h"
#include <embree3/rtcore.h>
#include <string>
#include <vector>

namespace penumbra {

// What a cut-out mesh's filter reads at each candidate hit (geometry/alpha_filter.cpp):
// the mesh's uvs (or its spherical mapping's centre) and vertex alphas, the
// material's alpha rule and its mask. It lives in TraceScene::Impl, at a fixed
// address while the scene exists.
struct AlphaCut {
  const TriangleMesh* mesh = nullptr;
  const AlphaMask* mask = nullptr;  // null: the material's alpha alone
  AlphaMode mode = AlphaMode::Opaque;
  float alpha = 1.0f, cutoff = 0.5f;
  UvTransform uv;     // the material's texture placement
  Vec3 centre{0.0f};  // spherical uvs on a mesh without its own
  uint32_t geomId = 0;
};

// The device and scene a TraceScene queries. It owns both handles: destroying it
// releases the scene, then the device (also when the constructor throws part way).
struct TraceScene::Impl {
  RTCDevice device = nullptr;
  RTCScene scene = nullptr;
  // The invisible medium boundaries (geometry/boundary_scene.cpp): a scene of their own,
  // null without any, so surface queries never see them and a scene without pays nothing.
  RTCScene boundaries = nullptr;
  struct BoundaryRef {
    bool sphere;
    uint32_t index;  // boundary mesh index; the spheres share one geometry and use primID
  };
  std::vector<BoundaryRef> boundaryRefs;  // by Embree geomID in `boundaries`
  std::string embreeError;  // first error Embree reported, if any (its error callback writes here)
  bool compact = false;     // the BVH's leaves index the vertices (BvhLayout::Compact)
  std::vector<AlphaCut> cuts;  // one per cut-out mesh, reserved up front (filters hold pointers)

  Impl() = default;
  Impl(const Impl&) = delete;
  Impl& operator=(const Impl&) = delete;
  ~Impl() {
    if (boundaries) rtcReleaseScene(boundaries);
    if (scene) rtcReleaseScene(scene);
    if (device) rtcReleaseDevice(device);
  }
};

// Creates the user geometry for all scene spheres (primID = sphere index). The
// spheres vector must outlive the Embree scene. (geometry/sphere_geometry.cpp)
RTCGeometry createSphereGeometry(RTCDevice device, const std::vector<Sphere>& spheres);

// A triangle mesh reading the scene's arrays in place where it can, with the cut-out
// filter when `cut` is set. (geometry/trace_scene.cpp)
RTCGeometry createMeshGeometry(RTCDevice device, const TriangleMesh& mesh, const AlphaCut* cut);

// The nearest hit of one ray in an Embree scene; false on a miss, a non-finite
// distance or a ray Embree would refuse. (geometry/trace_scene.cpp)
bool intersectScene(RTCScene scene, const Ray& ray, Hit& hit);

// Makes `geom` drop the hits `cut` cuts out, for intersection and occlusion queries
// alike, single rays and packets. (geometry/alpha_filter.cpp)
void attachAlphaFilter(RTCGeometry geom, const AlphaCut* cut);

}  // namespace penumbra
