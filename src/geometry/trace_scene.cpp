// Builds the Embree scene (triangle meshes + one user geometry of spheres) and
// answers ray queries; expands hits into surface records for shading.
#include "geometry/trace_scene.h"
#include "core/error.h"
#include "geometry/embree_impl.h"
#include "geometry/sphere_geometry.h"
#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>
#include <algorithm>
#include <stdexcept>
#include <string>

namespace penumbra {
namespace {

void onEmbreeError(void* userPtr, RTCError code, const char* message) {
  // Embree reports through a C callback; remember the first error and let the
  // constructor throw once control is back in C++.
  auto* first = static_cast<std::string*>(userPtr);
  if (first->empty()) first->assign(std::string("Embree error ") + std::to_string(code) + ": " + (message ? message : ""));
}

}  // namespace

RTCGeometry createMeshGeometry(RTCDevice device, const TriangleMesh& mesh, const AlphaCut* cut) {
  RTCGeometry geom = rtcNewGeometry(device, RTC_GEOMETRY_TYPE_TRIANGLE);
  // The scene outlives the tracer and never changes: Embree reads its arrays in place,
  // the vertices only where their storage has the padding its 16-byte loads read.
  static_assert(sizeof(Vec3) == 3 * sizeof(float) && sizeof(mesh.triangles[0]) == 3 * sizeof(unsigned));
  if (hasVertexPadding(mesh.positions)) {
    rtcSetSharedGeometryBuffer(geom, RTC_BUFFER_TYPE_VERTEX, 0, RTC_FORMAT_FLOAT3, mesh.positions.data(), 0,
                               sizeof(Vec3), mesh.positions.size());
  } else {
    auto* vertices = static_cast<Vec3*>(rtcSetNewGeometryBuffer(geom, RTC_BUFFER_TYPE_VERTEX, 0, RTC_FORMAT_FLOAT3,
                                                                sizeof(Vec3), mesh.positions.size()));
    std::copy(mesh.positions.begin(), mesh.positions.end(), vertices);
  }
  rtcSetSharedGeometryBuffer(geom, RTC_BUFFER_TYPE_INDEX, 0, RTC_FORMAT_UINT3, mesh.triangles.data(), 0,
                             sizeof(mesh.triangles[0]), mesh.triangles.size());
  if (cut) attachAlphaFilter(geom, cut);
  rtcCommitGeometry(geom);
  return geom;
}

bool compactBvh(size_t triangles, BvhLayout layout) {
  return layout == BvhLayout::Compact || (layout == BvhLayout::Auto && triangles >= kCompactBvhTriangles);
}

Vec2 sphericalUvPerWorld(float radius) {
  // u spans the equator (2 pi r) and v a meridian (pi r).
  return {1.0f / (2.0f * kPi * radius), 1.0f / (kPi * radius)};
}

Vec2 sphericalUv(const Vec3& d) {
  float u = 0.5f + std::atan2(d.x, d.z) / (2.0f * kPi);
  if (u >= 1.0f) u -= 1.0f;  // atan2 = pi maps to exactly 1: wrap it to the seam
  if (u < 0.0f) u += 1.0f;
  float v = std::acos(std::clamp(d.y, -1.0f, 1.0f)) / kPi;
  return {u, v};
}

// The interpolation's rounding is a few ulps of the vertices' magnitudes on each
// axis; along the normal that is dot(|n|, per-axis bound). Bounding by the largest
// vertex per axis (not the barycentric mix) also covers Embree's plane test, whose
// error in dot(n, v - o) is the same sum. A face normal to z at z ~ 0 gets an offset
// of ulps of z, not of its 3-unit width, so a wide 1e-6 slab keeps two faces.
// A plane at exactly z = 0 is exact in z and would get a 1-ulp (denormal) offset,
// which Embree's products flush to 0, hitting the plane again at t = 0: a floor of
// 2^-40 of the triangle's reach keeps those products normal at any scale.
void TraceScene::computeFrames(const TriangleMesh& mesh, TriangleFrame* frames) {
  tbb::parallel_for(tbb::blocked_range<size_t>(0, mesh.triangles.size(), 4096), [&](const auto& r) {
    for (size_t i = r.begin(); i != r.end(); ++i) {
      const auto& tri = mesh.triangles[i];
      frames[i] = frameOf(mesh.positions[tri[0]], mesh.positions[tri[1]], mesh.positions[tri[2]]);
    }
  });
}

TraceScene::TriangleFrame TraceScene::frameOf(const Vec3& p0, const Vec3& p1, const Vec3& p2) {
  const Vec3 ng = unitCross(p1 - p0, p2 - p0);
  const Vec3 extent = glm::max(glm::abs(p0), glm::max(glm::abs(p1), glm::abs(p2)));
  return {ng, std::max(gammaBound(7) * glm::dot(glm::abs(ng), extent), 0x1p-40f * maxComponent(extent)),
          gammaBound(7) * maxComponent(extent)};
}

TraceScene::TraceScene(const Scene& scene, bool robust, BvhLayout layout) : scene_(scene), impl_(std::make_unique<Impl>()) {
  // impl_ owns the handles and releases them on every exit, the throws below included.
  RTCDevice device = impl_->device = rtcNewDevice(nullptr);
  if (!device) throw std::runtime_error("cannot create Embree device");
  rtcSetDeviceErrorFunction(device, onEmbreeError, &impl_->embreeError);
  RTCScene rtcScene = impl_->scene = rtcNewScene(device);
  size_t triangles = 0;
  for (const TriangleMesh& mesh : scene.meshes) triangles += mesh.triangles.size();
  const bool compact = impl_->compact = compactBvh(triangles, layout);
  rtcSetSceneFlags(rtcScene, RTCSceneFlags((robust ? RTC_SCENE_FLAG_ROBUST : 0) | (compact ? RTC_SCENE_FLAG_COMPACT : 0)));
  nativePacketWidth_ = rtcGetDeviceProperty(device, RTC_DEVICE_PROPERTY_NATIVE_RAY16_SUPPORTED) ? 16
                       : rtcGetDeviceProperty(device, RTC_DEVICE_PROPERTY_NATIVE_RAY8_SUPPORTED) ? 8
                       : rtcGetDeviceProperty(device, RTC_DEVICE_PROPERTY_NATIVE_RAY4_SUPPORTED) ? 4
                                                                                                    : 1;
  packetWidth_ = nativePacketWidth_;

  // Cut-out meshes get a filter reading their AlphaCut; the vector never grows past
  // this, so the pointers Embree holds stay valid.
  impl_->cuts.reserve(scene.meshes.size());
  frames_.resize(triangles);
  size_t frameOffset = 0;
  for (size_t m = 0; m < scene.meshes.size(); ++m) {
    const TriangleMesh& mesh = scene.meshes[m];
    computeFrames(mesh, frames_.data() + frameOffset);
    Vec3 lo(kInf), hi(-kInf);
    for (const Vec3& p : mesh.positions) { lo = glm::min(lo, p); hi = glm::max(hi, p); }
    meshCentres_.push_back(mesh.positions.empty() ? Vec3(0.0f) : 0.5f * (lo + hi));
    meshRadii_.push_back(mesh.positions.empty() ? 1.0f : std::max(1e-6f, 0.5f * glm::length(hi - lo)));
    coloured_ = coloured_ || !mesh.colors.empty();
    if (mesh.triangles.empty()) continue;
    const AlphaCut* cut = alphaCutOf(scene, m, meshCentres_.back());
    RTCGeometry geom = createMeshGeometry(device, mesh, cut);
    unsigned id = rtcAttachGeometry(rtcScene, geom);
    if (cut) impl_->cuts.back().geomId = id;
    rtcReleaseGeometry(geom);
    if (geometries_.size() <= id) geometries_.resize(id + 1);
    geometries_[id] = {false, static_cast<uint32_t>(m), frameOffset};
    frameOffset += mesh.triangles.size();
  }
  if (!scene.spheres.empty()) {
    RTCGeometry geom = createSphereGeometry(device, scene.spheres);
    unsigned id = rtcAttachGeometry(rtcScene, geom);
    rtcReleaseGeometry(geom);
    if (geometries_.size() <= id) geometries_.resize(id + 1);
    geometries_[id] = {true, 0};
  }
  rtcCommitScene(rtcScene);
  if (!scene.boundarySpheres.empty() || !scene.boundaryMeshes.empty()) buildBoundaries(robust);
  RTCBounds b;
  rtcGetSceneBounds(rtcScene, &b);
  Vec3 lo(b.lower_x, b.lower_y, b.lower_z), hi(b.upper_x, b.upper_y, b.upper_z);
  if (isFinite(lo) && isFinite(hi) && glm::all(glm::lessThanEqual(lo, hi))) {
    bounds_.center = 0.5f * (lo + hi);
    bounds_.radius = std::max(0.5f * glm::length(hi - lo), 1e-6f);
  }
  if (!impl_->embreeError.empty()) throw std::runtime_error(impl_->embreeError);  // impl_ releases scene and device
}

const AlphaCut* TraceScene::alphaCutOf(const Scene& scene, size_t meshIndex, const Vec3& centre) {
  const TriangleMesh& mesh = scene.meshes[meshIndex];
  if (mesh.material < 0 || static_cast<size_t>(mesh.material) >= scene.materials.size()) return nullptr;
  const Material& m = scene.materials[mesh.material];
  if (m.alphaMode == AlphaMode::Opaque) return nullptr;
  if (!rtcGetDeviceProperty(impl_->device, RTC_DEVICE_PROPERTY_FILTER_FUNCTION_SUPPORTED)) {
    throw std::runtime_error("material " + m.name + " cuts out by alpha, and this Embree library was built without filter functions");
  }
  AlphaCut cut;
  cut.mesh = &mesh;
  cut.mask = m.alphaMask >= 0 && static_cast<size_t>(m.alphaMask) < scene.alphaMasks.size()
                 ? &scene.alphaMasks[m.alphaMask] : nullptr;
  cut.mode = m.alphaMode;
  cut.alpha = m.alpha;
  cut.cutoff = m.alphaCutoff;
  cut.uv = m.uvTransform();
  cut.centre = centre;
  impl_->cuts.push_back(cut);
  return &impl_->cuts.back();
}

TraceScene::~TraceScene() = default;  // here, where Impl is complete

bool intersectScene(RTCScene scene, const Ray& ray, Hit& hit) {
  if (!embreeAccepts(ray)) return false;
  RTCIntersectContext context;
  rtcInitIntersectContext(&context);
  RTCRayHit rh;
  rh.ray.org_x = ray.origin.x; rh.ray.org_y = ray.origin.y; rh.ray.org_z = ray.origin.z;
  rh.ray.dir_x = ray.dir.x; rh.ray.dir_y = ray.dir.y; rh.ray.dir_z = ray.dir.z;
  rh.ray.tnear = ray.tMin;
  rh.ray.tfar = ray.tMax;
  rh.ray.time = 0.0f;
  rh.ray.mask = ~0u;
  rh.ray.id = 0;
  rh.ray.flags = 0;
  rh.hit.geomID = RTC_INVALID_GEOMETRY_ID;
  rh.hit.instID[0] = RTC_INVALID_GEOMETRY_ID;
  rtcIntersect1(scene, &context, &rh);
  // A non-finite distance can only come from geometry at the edge of float range;
  // treating it as a miss keeps NaN out of every position and offset after it.
  if (rh.hit.geomID == RTC_INVALID_GEOMETRY_ID || !std::isfinite(rh.ray.tfar)) return false;
  hit.t = rh.ray.tfar;
  hit.u = rh.hit.u;
  hit.v = rh.hit.v;
  hit.geomId = rh.hit.geomID;
  hit.primId = rh.hit.primID;
  return true;
}

bool TraceScene::intersect(const Ray& ray, Hit& hit) const { return intersectScene(impl_->scene, ray, hit); }

bool TraceScene::occluded(const Ray& ray) const {
  if (!embreeAccepts(ray)) return true;  // no light along a ray that is not one
  RTCIntersectContext context;
  rtcInitIntersectContext(&context);
  RTCRay r;
  r.org_x = ray.origin.x; r.org_y = ray.origin.y; r.org_z = ray.origin.z;
  r.dir_x = ray.dir.x; r.dir_y = ray.dir.y; r.dir_z = ray.dir.z;
  r.tnear = ray.tMin;
  r.tfar = ray.tMax;
  r.time = 0.0f;
  r.mask = ~0u;
  r.id = 0;
  r.flags = 0;
  rtcOccluded1(impl_->scene, &context, &r);
  return r.tfar < 0.0f;
}

int TraceScene::materialOf(const Hit& hit) const {
  const GeometryRef& g = geometries_[hit.geomId];
  return g.sphere ? scene_.spheres[hit.primId].material : scene_.meshes[g.index].material;
}

SurfaceRecord TraceScene::surface(const Ray& ray, const Hit& hit, uint8_t fields) const {
  return geometries_[hit.geomId].sphere ? sphereSurface(ray, hit, fields)
                                        : meshSurface(ray, hit, fields);
}

int TraceScene::mediumBeyond(const Hit& hit, const SurfaceRecord& s, const Vec3& dir, int current) const {
  const GeometryRef& g = geometries_[hit.geomId];
  const MediumInterface& mi = g.sphere ? scene_.spheres[hit.primId].media : scene_.meshes[g.index].media;
  if (!mi.separates) return current;
  // ng faces the arriving ray; frontFace says whether that side is the outside.
  const Vec3 outward = s.frontFace == mi.entersFromFront() ? s.ng : -s.ng;
  return glm::dot(dir, outward) < 0.0f ? mi.inside : mi.outside;
}

SurfaceRecord TraceScene::sphereSurface(const Ray& ray, const Hit& hit, uint8_t fields) const {
  return sphereRecord(scene_.spheres[hit.primId], ray, hit.t, fields);
}

SurfaceRecord TraceScene::sphereRecord(const Sphere& s, const Ray& ray, float t, uint8_t fields) {
  SurfaceRecord rec;
  // The normal in double: o + t d lands within float rounding of the centre's
  // neighbourhood on a tiny sphere, where a float p - c would cancel to zero.
  const glm::dvec3 c(s.center);
  const glm::dvec3 d = glm::dvec3(ray.origin) + double(t) * glm::dvec3(ray.dir) - c;
  const double len = glm::length(d);
  const Vec3 n = len > 0.0 ? Vec3(d / len) : -ray.dir;
  // Re-project onto the sphere: removes the error of o + t d at large t. What is
  // left is the rounding of c + r n: a few ulps of |c| + r per axis.
  rec.position = s.center + s.radius * n;
  rec.error = rec.spread = gammaBound(5) * (maxComponent(glm::abs(s.center)) + s.radius);
  if (fields & kSurfaceUv) {
    rec.uv = sphericalUv(n);
    rec.uvPerWorld = sphericalUvPerWorld(s.radius);
  }
  rec.material = s.material;
  rec.frontFace = glm::dot(n, ray.dir) < 0.0f;
  rec.ng = rec.ns = rec.frontFace ? n : -n;
  return rec;
}

SurfaceRecord TraceScene::meshSurface(const Ray& ray, const Hit& hit, uint8_t fields) const {
  const TriangleMesh& mesh = scene_.meshes[geometries_[hit.geomId].index];
  const auto& tri = mesh.triangles[hit.primId];
  float w = 1.0f - hit.u - hit.v;
  const Vec3 &p0 = mesh.positions[tri[0]], &p1 = mesh.positions[tri[1]], &p2 = mesh.positions[tri[2]];
  const TriangleFrame& frame = frames_[geometries_[hit.geomId].frames + hit.primId];
  SurfaceRecord rec;
  // Barycentric interpolation is exact to float precision on the triangle's
  // plane, unlike o + t d, which drifts with the ray length.
  rec.position = w * p0 + hit.u * p1 + hit.v * p2;
  Vec3 ng = frame.ng;
  rec.error = frame.error;
  rec.spread = frame.spread;
  Vec3 ns = ng;
  if ((fields & kSurfaceShadingNormal) && !mesh.normals.empty()) {
    Vec3 n = w * mesh.normals[tri[0]] + hit.u * mesh.normals[tri[1]] + hit.v * mesh.normals[tri[2]];
    float len = glm::length(n);
    if (len > 1e-12f) ns = n / len;
  }
  const float radius = meshRadii_[geometries_[hit.geomId].index];
  if (!(fields & kSurfaceUv)) {
    // Not asked for: leave the defaults.
  } else if (!mesh.uvs.empty()) {
    const Vec2 &t0 = mesh.uvs[tri[0]], &t1 = mesh.uvs[tri[1]], &t2 = mesh.uvs[tri[2]];
    rec.uv = w * t0 + hit.u * t1 + hit.v * t2;
    // Isotropic scale from the triangle's uv area over its world area.
    Vec2 a = t1 - t0, b = t2 - t0;
    float uvArea = std::abs(a.x * b.y - a.y * b.x);
    float worldArea = glm::length(glm::cross(p1 - p0, p2 - p0));
    float scale = worldArea > 0.0f ? std::sqrt(uvArea / worldArea) : 0.0f;
    rec.uvPerWorld = Vec2(scale);
  } else {
    rec.uvPerWorld = sphericalUvPerWorld(radius);
    Vec3 d = rec.position - meshCentres_[geometries_[hit.geomId].index];
    float len = glm::length(d);
    rec.uv = sphericalUv(len > 0.0f ? d / len : Vec3(0.0f, 1.0f, 0.0f));
  }
  rec.material = mesh.material;
  rec.frontFace = glm::dot(ng, ray.dir) < 0.0f;
  if (!rec.frontFace) { ng = -ng; ns = -ns; }
  // An interpolated normal can lean past the silhouette; never let it face away
  // from the viewer, or Phong would light the back of the surface.
  if (glm::dot(ns, ray.dir) > 0.0f) ns = ng;
  rec.ng = ng;
  rec.ns = ns;
  return rec;
}

glm::vec4 TraceScene::tangent(const Hit& hit) const {
  const GeometryRef& g = geometries_[hit.geomId];
  if (g.sphere) return glm::vec4(0.0f);
  const TriangleMesh& mesh = scene_.meshes[g.index];
  if (mesh.tangents.empty()) return glm::vec4(0.0f);
  const auto& tri = mesh.triangles[hit.primId];
  const float w = 1.0f - hit.u - hit.v;
  const glm::vec4 &t0 = mesh.tangents[tri[0]], &t1 = mesh.tangents[tri[1]], &t2 = mesh.tangents[tri[2]];
  return glm::vec4(Vec3(w * t0 + hit.u * t1 + hit.v * t2), t0.w < 0.0f ? -1.0f : 1.0f);
}

glm::vec4 TraceScene::meshColor(const Hit& hit) const {
  const GeometryRef& g = geometries_[hit.geomId];
  if (g.sphere) return glm::vec4(1.0f);
  const TriangleMesh& mesh = scene_.meshes[g.index];
  return mesh.colors.empty() ? glm::vec4(1.0f) : vertexColorAt(mesh, hit.primId, hit.u, hit.v);
}

glm::vec4 vertexColorAt(const TriangleMesh& mesh, uint32_t prim, float u, float v) {
  const auto& tri = mesh.triangles[prim];
  const float w = 1.0f - u - v;
  const glm::vec4 c = w * mesh.colors[tri[0]] + u * mesh.colors[tri[1]] + v * mesh.colors[tri[2]];
  return glm::clamp(c, 0.0f, 1.0f);
}

}  // namespace penumbra
