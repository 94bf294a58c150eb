// Invisible medium boundaries (Scene::boundarySpheres, boundaryMeshes) in an Embree
// scene of their own: only a ray's walk through media queries it, surfaces never see it.
#include "core/error.h"
#include "geometry/embree_impl.h"
#include "geometry/trace_scene.h"

namespace penumbra {

void TraceScene::buildBoundaries(bool robust) {
  RTCScene boundaries = impl_->boundaries = rtcNewScene(impl_->device);
  rtcSetSceneFlags(boundaries, robust ? RTC_SCENE_FLAG_ROBUST : RTC_SCENE_FLAG_NONE);
  auto attach = [&](RTCGeometry geom, Impl::BoundaryRef ref) {
    const unsigned id = rtcAttachGeometry(boundaries, geom);
    rtcReleaseGeometry(geom);
    if (impl_->boundaryRefs.size() <= id) impl_->boundaryRefs.resize(id + 1);
    impl_->boundaryRefs[id] = ref;
  };
  const std::vector<TriangleMesh>& meshes = scene_.boundaryMeshes;
  for (size_t m = 0; m < meshes.size(); ++m) {
    if (meshes[m].triangles.empty()) continue;
    attach(createMeshGeometry(impl_->device, meshes[m], nullptr), {false, static_cast<uint32_t>(m)});
  }
  if (!scene_.boundarySpheres.empty()) attach(createSphereGeometry(impl_->device, scene_.boundarySpheres), {true, 0});
  rtcCommitScene(boundaries);
}

bool TraceScene::hasBoundaries() const { return impl_->boundaries != nullptr; }

bool TraceScene::nextBoundary(const Ray& ray, float tMax, BoundaryCrossing& out) const {
  if (!impl_->boundaries) return false;
  Ray r = ray;
  r.tMax = std::min(ray.tMax, tMax);
  Hit hit;
  if (!intersectScene(impl_->boundaries, r, hit)) return false;
  const Impl::BoundaryRef& g = impl_->boundaryRefs[hit.geomId];
  SurfaceRecord s;
  const MediumInterface* media;
  if (g.sphere) {
    const Sphere& sphere = scene_.boundarySpheres[hit.primId];
    s = sphereRecord(sphere, ray, hit.t, kSurfaceGeometric);
    media = &sphere.media;
  } else {
    // Only what the next ray's origin needs: the point on the triangle, its normal
    // facing the ray and its rounding bounds (as meshSurface computes them).
    const TriangleMesh& mesh = scene_.boundaryMeshes[g.index];
    const auto& tri = mesh.triangles[hit.primId];
    const Vec3 &p0 = mesh.positions[tri[0]], &p1 = mesh.positions[tri[1]], &p2 = mesh.positions[tri[2]];
    const TriangleFrame frame = frameOf(p0, p1, p2);
    s.position = (1.0f - hit.u - hit.v) * p0 + hit.u * p1 + hit.v * p2;
    s.error = frame.error;
    s.spread = frame.spread;
    s.frontFace = glm::dot(frame.ng, ray.dir) < 0.0f;
    s.ng = s.ns = s.frontFace ? frame.ng : -frame.ng;
    s.material = -1;
    media = &mesh.media;
  }
  // ng faces the arriving ray; frontFace says whether that side is the outside.
  out.t = hit.t;
  out.beyond = s.frontFace == media->entersFromFront() ? media->inside : media->outside;
  out.surface = s;
  return true;
}

}  // namespace penumbra
