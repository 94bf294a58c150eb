// TraceScene's packet queries: rays in SoA Embree packets (RTCRayHit16/8/4) with
// valid masks and the coherent flag (but for occlusion in a compact BVH); each lane
// answers as the single-ray query would.
#include "geometry/trace_scene.h"
#include "geometry/embree_impl.h"
#include <algorithm>
#include <cmath>

namespace penumbra {
namespace {

// One packet width's Embree types and entry points.
template <int K> struct PacketApi;
template <> struct PacketApi<16> {
  using RayHit = RTCRayHit16;
  using RayOnly = RTCRay16;
  static void intersect(const int* v, RTCScene s, RTCIntersectContext* c, RayHit* r) { rtcIntersect16(v, s, c, r); }
  static void occluded(const int* v, RTCScene s, RTCIntersectContext* c, RayOnly* r) { rtcOccluded16(v, s, c, r); }
};
template <> struct PacketApi<8> {
  using RayHit = RTCRayHit8;
  using RayOnly = RTCRay8;
  static void intersect(const int* v, RTCScene s, RTCIntersectContext* c, RayHit* r) { rtcIntersect8(v, s, c, r); }
  static void occluded(const int* v, RTCScene s, RTCIntersectContext* c, RayOnly* r) { rtcOccluded8(v, s, c, r); }
};
template <> struct PacketApi<4> {
  using RayHit = RTCRayHit4;
  using RayOnly = RTCRay4;
  static void intersect(const int* v, RTCScene s, RTCIntersectContext* c, RayHit* r) { rtcIntersect4(v, s, c, r); }
  static void occluded(const int* v, RTCScene s, RTCIntersectContext* c, RayOnly* r) { rtcOccluded4(v, s, c, r); }
};

// Fills lane i of an SoA ray (RTCRay4/8/16 share the field names). Returns false for
// a ray Embree would assert on: its lane stays invalid, which reads as a miss.
template <class R>
bool fillLane(R& r, int i, const Ray& ray) {
  if (!embreeAccepts(ray)) return false;
  r.org_x[i] = ray.origin.x; r.org_y[i] = ray.origin.y; r.org_z[i] = ray.origin.z;
  r.dir_x[i] = ray.dir.x; r.dir_y[i] = ray.dir.y; r.dir_z[i] = ray.dir.z;
  r.tnear[i] = ray.tMin;
  r.tfar[i] = ray.tMax;
  r.time[i] = 0.0f;
  r.mask[i] = ~0u;
  r.id[i] = static_cast<unsigned>(i);
  r.flags[i] = 0;
  return true;
}

RTCIntersectContext packetContext(bool coherent) {
  RTCIntersectContext context;
  rtcInitIntersectContext(&context);
  context.flags = coherent ? RTC_INTERSECT_CONTEXT_FLAG_COHERENT : RTC_INTERSECT_CONTEXT_FLAG_INCOHERENT;
  return context;
}

template <int K>
void intersectK(RTCScene scene, const Ray* rays, int n, Hit* hits) {
  RTCIntersectContext context = packetContext(true);
  for (int base = 0; base < n; base += K) {
    const int lanes = std::min(K, n - base);
    alignas(64) typename PacketApi<K>::RayHit rh;
    alignas(64) int valid[K];
    for (int i = 0; i < K; ++i) {
      valid[i] = i < lanes && fillLane(rh.ray, i, rays[base + i]) ? -1 : 0;
      rh.hit.geomID[i] = RTC_INVALID_GEOMETRY_ID;
      rh.hit.instID[0][i] = RTC_INVALID_GEOMETRY_ID;
    }
    PacketApi<K>::intersect(valid, scene, &context, &rh);
    for (int i = 0; i < lanes; ++i) {
      Hit& hit = hits[base + i];
      hit = Hit{};
      // As intersect: a non-finite distance is a miss.
      if (!valid[i] || rh.hit.geomID[i] == RTC_INVALID_GEOMETRY_ID || !std::isfinite(rh.ray.tfar[i])) continue;
      hit.t = rh.ray.tfar[i];
      hit.u = rh.hit.u[i];
      hit.v = rh.hit.v[i];
      hit.geomId = rh.hit.geomID[i];
      hit.primId = rh.hit.primID[i];
    }
  }
}

template <int K>
void occludedK(RTCScene scene, const Ray* rays, int n, uint8_t* blocked, bool coherent) {
  RTCIntersectContext context = packetContext(coherent);
  for (int base = 0; base < n; base += K) {
    const int lanes = std::min(K, n - base);
    alignas(64) typename PacketApi<K>::RayOnly r;
    alignas(64) int valid[K];
    for (int i = 0; i < K; ++i) valid[i] = i < lanes && fillLane(r, i, rays[base + i]) ? -1 : 0;
    PacketApi<K>::occluded(valid, scene, &context, &r);
    // As occluded: a ray that is not one carries no light.
    for (int i = 0; i < lanes; ++i) blocked[base + i] = !valid[i] || r.tfar[i] < 0.0f;
  }
}

}  // namespace

void TraceScene::setPacketWidth(int width) {
  int w = width >= 16 ? 16 : width >= 8 ? 8 : width >= 4 ? 4 : 1;
  while (w > nativePacketWidth_) w = w == 4 ? 1 : w / 2;
  packetWidth_ = w;
}

void TraceScene::intersectPacket(const Ray* rays, int n, Hit* hits) const {
  switch (packetWidth_) {
    case 16: intersectK<16>(impl_->scene, rays, n, hits); break;
    case 8: intersectK<8>(impl_->scene, rays, n, hits); break;
    case 4: intersectK<4>(impl_->scene, rays, n, hits); break;
    default:
      for (int i = 0; i < n; ++i) {
        Hit h;
        hits[i] = intersect(rays[i], h) ? h : Hit{};
      }
      return;
  }
  // A ray through an edge shared by two triangles (a box's corner, a quad's diagonal)
  // meets both at the same t, and the nearer-or-equal test keeps whichever the
  // traversal visited first: packet and single-ray traversals visit them in different
  // orders. Hits that close to an edge are traced again alone, so the answer is the
  // single ray's. (They are ~1e-4 of the hits. A tie away from edges is not caught:
  // coplanar overlapping faces seen by the camera, or two surfaces crossing exactly at
  // the hit point, may keep the other face.)
  constexpr float kEdge = 1e-4f;
  for (int i = 0; i < n; ++i) {
    const Hit& h = hits[i];
    if (!h.valid() || geometries_[h.geomId].sphere) continue;
    if (std::min(std::min(h.u, h.v), 1.0f - h.u - h.v) >= kEdge) continue;
    Hit alone;
    hits[i] = intersect(rays[i], alone) ? alone : Hit{};
  }
}

void TraceScene::occludedPacket(const Ray* rays, int n, uint8_t* blocked) const {
  // Embree's coherent occlusion kernel for robust compact leaves (16 wide: AVX-512)
  // never returns; the incoherent one answers the same.
  const bool coherent = !impl_->compact;
  switch (packetWidth_) {
    case 16: return occludedK<16>(impl_->scene, rays, n, blocked, coherent);
    case 8: return occludedK<8>(impl_->scene, rays, n, blocked, coherent);
    case 4: return occludedK<4>(impl_->scene, rays, n, blocked, coherent);
    default:
      for (int i = 0; i < n; ++i) blocked[i] = occluded(rays[i]);
  }
}

}  // namespace penumbra
