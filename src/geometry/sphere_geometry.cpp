// Embree user-geometry callbacks for analytic spheres.
#include "geometry/sphere_geometry.h"
#include "geometry/embree_impl.h"
#include <cmath>

namespace penumbra {

double intersectSphere(const Sphere& s, const Vec3& o, const Vec3& d, double tMin, double tMax) {
  // Work along the unit direction so the discriminant is r^2 - |f - (f.d)d|^2:
  // the perpendicular distance is computed directly instead of as the difference
  // of two large numbers, which keeps far-away and tiny spheres exact.
  double dx = d.x, dy = d.y, dz = d.z;
  double len = std::sqrt(dx * dx + dy * dy + dz * dz);
  if (!(len > 0.0)) return -1.0;
  dx /= len; dy /= len; dz /= len;
  double fx = double(o.x) - s.center.x, fy = double(o.y) - s.center.y, fz = double(o.z) - s.center.z;
  double b = -(fx * dx + fy * dy + fz * dz);
  double px = fx + b * dx, py = fy + b * dy, pz = fz + b * dz;
  double r2 = double(s.radius) * s.radius;
  double disc = r2 - (px * px + py * py + pz * pz);
  if (disc < 0.0) return -1.0;
  double c = fx * fx + fy * fy + fz * fz - r2;
  double q = b + std::copysign(std::sqrt(disc), b);
  double t0 = q != 0.0 ? c / q : 0.0, t1 = q;
  if (t0 > t1) std::swap(t0, t1);
  t0 /= len; t1 /= len;  // back to the caller's parametrisation
  if (t0 > tMin && t0 < tMax) return t0;
  if (t1 > tMin && t1 < tMax) return t1;
  return -1.0;
}

namespace {

void sphereBounds(const RTCBoundsFunctionArguments* args) {
  const auto& spheres = *static_cast<const std::vector<Sphere>*>(args->geometryUserPtr);
  const Sphere& s = spheres[args->primID];
  RTCBounds* b = args->bounds_o;
  b->lower_x = s.center.x - s.radius; b->lower_y = s.center.y - s.radius; b->lower_z = s.center.z - s.radius;
  b->upper_x = s.center.x + s.radius; b->upper_y = s.center.y + s.radius; b->upper_z = s.center.z + s.radius;
}

void sphereIntersect(const RTCIntersectFunctionNArguments* args) {
  const auto& spheres = *static_cast<const std::vector<Sphere>*>(args->geometryUserPtr);
  const Sphere& s = spheres[args->primID];
  RTCRayN* ray = RTCRayHitN_RayN(args->rayhit, args->N);
  RTCHitN* hit = RTCRayHitN_HitN(args->rayhit, args->N);
  for (unsigned i = 0; i < args->N; ++i) {
    if (!args->valid[i]) continue;
    Vec3 o(RTCRayN_org_x(ray, args->N, i), RTCRayN_org_y(ray, args->N, i), RTCRayN_org_z(ray, args->N, i));
    Vec3 d(RTCRayN_dir_x(ray, args->N, i), RTCRayN_dir_y(ray, args->N, i), RTCRayN_dir_z(ray, args->N, i));
    float& tfar = RTCRayN_tfar(ray, args->N, i);
    double t = intersectSphere(s, o, d, RTCRayN_tnear(ray, args->N, i), tfar);
    if (t < 0.0) continue;
    tfar = static_cast<float>(t);
    Vec3 ng = o + static_cast<float>(t) * d - s.center;
    RTCHitN_Ng_x(hit, args->N, i) = ng.x;
    RTCHitN_Ng_y(hit, args->N, i) = ng.y;
    RTCHitN_Ng_z(hit, args->N, i) = ng.z;
    RTCHitN_u(hit, args->N, i) = 0.0f;
    RTCHitN_v(hit, args->N, i) = 0.0f;
    RTCHitN_primID(hit, args->N, i) = args->primID;
    RTCHitN_geomID(hit, args->N, i) = args->geomID;
    RTCHitN_instID(hit, args->N, i, 0) = args->context->instID[0];
  }
}

void sphereOccluded(const RTCOccludedFunctionNArguments* args) {
  const auto& spheres = *static_cast<const std::vector<Sphere>*>(args->geometryUserPtr);
  const Sphere& s = spheres[args->primID];
  for (unsigned i = 0; i < args->N; ++i) {
    if (!args->valid[i]) continue;
    Vec3 o(RTCRayN_org_x(args->ray, args->N, i), RTCRayN_org_y(args->ray, args->N, i),
           RTCRayN_org_z(args->ray, args->N, i));
    Vec3 d(RTCRayN_dir_x(args->ray, args->N, i), RTCRayN_dir_y(args->ray, args->N, i),
           RTCRayN_dir_z(args->ray, args->N, i));
    float& tfar = RTCRayN_tfar(args->ray, args->N, i);
    if (intersectSphere(s, o, d, RTCRayN_tnear(args->ray, args->N, i), tfar) >= 0.0) tfar = -kInf;
  }
}

}  // namespace

RTCGeometry createSphereGeometry(RTCDevice device, const std::vector<Sphere>& spheres) {
  RTCGeometry geom = rtcNewGeometry(device, RTC_GEOMETRY_TYPE_USER);
  rtcSetGeometryUserPrimitiveCount(geom, static_cast<unsigned>(spheres.size()));
  rtcSetGeometryUserData(geom, const_cast<std::vector<Sphere>*>(&spheres));
  rtcSetGeometryBoundsFunction(geom, sphereBounds, nullptr);
  rtcSetGeometryIntersectFunction(geom, sphereIntersect);
  rtcSetGeometryOccludedFunction(geom, sphereOccluded);
  rtcCommitGeometry(geom);
  return geom;
}

}  // namespace penumbra
