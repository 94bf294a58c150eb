// The cut-out filter: Embree calls it for every candidate hit on a mesh whose
// material has an alpha mode, before accepting the hit, and it drops the hits the
// material's alpha cuts out. Camera rays, shadow rays and photons all go through it.
#include "geometry/embree_impl.h"
#include "core/math.h"

namespace penumbra {
namespace {

// The hit's texture coordinates, as meshSurface computes them (its uvs, or the
// spherical mapping about the mesh's centre), placed as the material's textures are.
Vec2 hitUv(const AlphaCut& cut, uint32_t prim, float u, float v) {
  const TriangleMesh& mesh = *cut.mesh;
  const auto& tri = mesh.triangles[prim];
  const float w = 1.0f - u - v;
  if (!mesh.uvs.empty()) {
    return cut.uv.apply(w * mesh.uvs[tri[0]] + u * mesh.uvs[tri[1]] + v * mesh.uvs[tri[2]]);
  }
  const Vec3 p = w * mesh.positions[tri[0]] + u * mesh.positions[tri[1]] + v * mesh.positions[tri[2]];
  const Vec3 d = p - cut.centre;
  const float len = glm::length(d);
  return cut.uv.apply(sphericalUv(len > 0.0f ? d / len : Vec3(0.0f, 1.0f, 0.0f)));
}

// One lane: whether the candidate hit stays. A blended surface keys its coin by the
// ray (origin and direction bits) and the primitive, never by thread or call order,
// so the same ray meets the same surface on every run and in every query kind.
bool keeps(const AlphaCut& cut, RTCRayN* ray, RTCHitN* hit, unsigned n, unsigned i) {
  const uint32_t prim = RTCHitN_primID(hit, n, i);
  float coverage = cut.alpha;
  const float u = RTCHitN_u(hit, n, i), v = RTCHitN_v(hit, n, i);
  if (cut.mask) coverage *= cut.mask->at(hitUv(cut, prim, u, v));
  if (!cut.mesh->colors.empty()) coverage *= vertexColorAt(*cut.mesh, prim, u, v).a;
  if (cut.mode != AlphaMode::Blend) return alphaKeeps(cut.mode, coverage, cut.cutoff, 0);
  if (coverage >= 1.0f) return true;
  if (coverage <= 0.0f) return false;
  const uint64_t origin = hashKey(uint64_t(floatBits(RTCRayN_org_x(ray, n, i))) << 32 | floatBits(RTCRayN_org_y(ray, n, i)),
                                  uint64_t(floatBits(RTCRayN_org_z(ray, n, i))) << 32 | floatBits(RTCRayN_dir_x(ray, n, i)));
  const uint64_t key = hashKey(origin, uint64_t(floatBits(RTCRayN_dir_y(ray, n, i))) << 32 | floatBits(RTCRayN_dir_z(ray, n, i)),
                               uint64_t(cut.geomId) << 32 | prim);
  return alphaKeeps(AlphaMode::Blend, coverage, cut.cutoff, key);
}

// The same function for both queries: a cut-out drops a hit and an occlusion alike.
void alphaFilter(const RTCFilterFunctionNArguments* args) {
  const auto& cut = *static_cast<const AlphaCut*>(args->geometryUserPtr);
  for (unsigned i = 0; i < args->N; ++i) {
    if (args->valid[i] == 0) continue;
    if (!keeps(cut, args->ray, args->hit, args->N, i)) args->valid[i] = 0;
  }
}

}  // namespace

void attachAlphaFilter(RTCGeometry geom, const AlphaCut* cut) {
  rtcSetGeometryUserData(geom, const_cast<AlphaCut*>(cut));
  rtcSetGeometryIntersectFilterFunction(geom, alphaFilter);
  rtcSetGeometryOccludedFilterFunction(geom, alphaFilter);
}

}  // namespace penumbra
