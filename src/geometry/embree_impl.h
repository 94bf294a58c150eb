// Private to src/geometry: the Embree side of TraceScene. Only the geometry .cpp
// files include this header (and with it <embree3/rtcore.h>); the rest of the
// renderer sees TraceScene through trace_scene.h without any Embree type.
#pragma once
#include "core/scene.h"
#include "geometry/trace_scene.h"
#include <embree3/rtcore.h>
#include <string>
#include <vector>

namespace penumbra {

// The device and scene a TraceScene queries. It owns both handles: destroying it
// releases the scene, then the device (also when the constructor throws part way).
struct TraceScene::Impl {
  RTCDevice device = nullptr;
  RTCScene scene = nullptr;
  std::string embreeError;  // first error Embree reported, if any (its error callback writes here)

  Impl() = default;
  Impl(const Impl&) = delete;
  Impl& operator=(const Impl&) = delete;
  ~Impl() {
    if (scene) rtcReleaseScene(scene);
    if (device) rtcReleaseDevice(device);
  }
};

// Creates the user geometry for all scene spheres (primID = sphere index). The
// spheres vector must outlive the Embree scene. (geometry/sphere_geometry.cpp)
RTCGeometry createSphereGeometry(RTCDevice device, const std::vector<Sphere>& spheres);

}  // namespace penumbra
