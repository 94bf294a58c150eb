// The Embree 3 device and scene built from a Scene: ray queries for the tracer
// and the photon pass, and the expansion of a small Hit into a SurfaceRecord.
// Embree stays behind the .cpp files (TraceScene::Impl, geometry/embree_impl.h):
// the translation units that include this header do not compile Embree's headers.
#pragma once
#include "core/light_sample.h"
#include "core/scene.h"
#include "geometry/ray.h"
#include <memory>
#include <string>
#include <vector>

namespace penumbra {

struct AlphaCut;  // a cut-out mesh's filter data (geometry/embree_impl.h)

// Which SurfaceRecord fields a caller needs. Position, geometric normal, side and
// material are always filled (every caller needs them, and they cost a few flops);
// interpolated normals and texture coordinates only on request, so photon and
// shadow hits skip the uv work.
enum SurfaceFields : uint8_t {
  kSurfaceGeometric = 0,
  kSurfaceShadingNormal = 1 << 0,  // ns interpolated from vertex normals (else ns = ng)
  kSurfaceUv = 1 << 1,             // uv and uvPerWorld
  kSurfaceAll = kSurfaceShadingNormal | kSurfaceUv,
};

// Everything shading needs about a hit. Normals are unit length and face the
// side the ray came from; frontFace says whether that is the outside (the side
// the geometric normal points to), which decides entering versus leaving glass.
struct SurfaceRecord {
  Vec3 position{0.0f};
  Vec3 ng{0.0f, 0.0f, 1.0f};  // geometric normal, facing the incoming ray
  Vec3 ns{0.0f, 0.0f, 1.0f};  // shading normal, facing the incoming ray
  Vec2 uv{0.0f};
  Vec2 uvPerWorld{1.0f};  // uv change per unit of world distance (u, v): texture filter widths
  float error = 0.0f;  // bound on position's distance from the true surface along ng
  float spread = 0.0f; // bound on its error in any direction (along the surface too)
  int material = 0;
  bool frontFace = true;
};

// A secondary ray's origin: the hit point moved past its own error bound, to dir's side.
inline Vec3 spawnOrigin(const SurfaceRecord& s, const Vec3& dir) {
  return offsetRayOrigin(s.position, s.ng, s.error, dir);
}

// How Embree lays out the BVH's leaves. Fast: each leaf holds its triangles' vertices
// (Embree's default). Compact (RTC_SCENE_FLAG_COMPACT): indices into the meshes' own
// vertices, about half the BVH's bytes for slower rays (docs/PERFORMANCE.md, Memory).
// Auto: compact from kCompactBvhTriangles triangles on, where the default layout
// would outweigh the rest of a render's memory.
enum class BvhLayout { Auto, Fast, Compact };
constexpr size_t kCompactBvhTriangles = 1000000;
bool compactBvh(size_t triangles, BvhLayout layout = BvhLayout::Auto);

class TraceScene {
 public:
  // robust: Embree's watertight mode (RTC_SCENE_FLAG_ROBUST). Without it, rays through
  // a shared edge of two triangles can slip between them (holes in a scaled room);
  // docs/PERFORMANCE.md measures what it costs. Off only for that measurement.
  explicit TraceScene(const Scene& scene, bool robust = true, BvhLayout layout = BvhLayout::Auto);
  ~TraceScene();
  TraceScene(const TraceScene&) = delete;
  TraceScene& operator=(const TraceScene&) = delete;

  bool intersect(const Ray& ray, Hit& hit) const;
  bool occluded(const Ray& ray) const;
  SurfaceRecord surface(const Ray& ray, const Hit& hit, uint8_t fields = kSurfaceAll) const;
  // A mesh hit's tangent interpolated from its mesh's (normal-mapped meshes only): xyz
  // along +u (not unit, not yet orthogonal to ns, never flipped with it), w the
  // bitangent's sign; all 0 on a sphere or a mesh without tangents. Apart from the
  // record, which stays small for the many hits without a normal map.
  glm::vec4 tangent(const Hit& hit) const;
  // A hit's vertex colour (linear RGBA, interpolated as uvs are): the mesh's colours,
  // 1 on a sphere or a mesh without them. Apart from the record, as the tangent is; a
  // scene without colours answers from one flag.
  glm::vec4 vertexColor(const Hit& hit) const { return coloured_ ? meshColor(hit) : glm::vec4(1.0f); }

  // Coherent rays (camera rays of a tile, their shadow rays to one light) as Embree
  // packets of packetWidth() lanes with the coherent flag (geometry/packet_trace.cpp).
  // Ray by ray the answers equal intersect's and occluded's: a miss leaves hits[i]
  // invalid (Hit{}), blocked[i] is 1 where occluded would say true.
  void intersectPacket(const Ray* rays, int n, Hit* hits) const;
  void occludedPacket(const Ray* rays, int n, uint8_t* blocked) const;
  // 16, 8 or 4: the widest packet the device runs natively; 1 when it has none (then
  // the packet calls loop over single rays).
  int packetWidth() const { return packetWidth_; }
  // Narrower packets for tests and benchmarks: 1, 4, 8 or 16, capped at the native width.
  void setPacketWidth(int width);

  // The material index of a hit, without building its record: lets a caller
  // decide which fields it needs (uv only for textured materials).
  int materialOf(const Hit& hit) const;

  // Participating media (scenes with a medium; core/media/medium.h). The medium a ray
  // leaving this hit towards `dir` travels in, when it arrived in `current`: a closed
  // object's inside or outside, or `current` where the surface separates no media.
  int mediumBeyond(const Hit& hit, const SurfaceRecord& s, const Vec3& dir, int current) const;
  // The first invisible medium boundary (Scene::boundarySpheres and boundaryMeshes)
  // along `ray` before tMax: its distance and the medium beyond it, towards ray.dir.
  struct BoundaryCrossing {
    float t = kInf;
    int beyond = kNoMedium;
    SurfaceRecord surface;  // for the next ray's origin (spawnOrigin)
  };
  // False (at once) in a scene without boundaries.
  bool nextBoundary(const Ray& ray, float tMax, BoundaryCrossing& out) const;
  // Boundaries one walk (a ray's, a photon's flight) crosses at most: nested media are a
  // handful deep; a degenerate mesh must not hold a ray forever.
  static constexpr int kMaxBoundaryCrossings = 64;
  bool hasBoundaries() const;

  // A sphere around all geometry (Embree's bounds): directional lights emit from it.
  SceneSphere boundingSphere() const { return bounds_; }

  const Scene& scene() const { return scene_; }

 private:
  // The Embree device and scene (geometry/embree_impl.h, for the geometry .cpp files only).
  struct Impl;

  struct GeometryRef {
    bool sphere;
    uint32_t index;  // mesh index; spheres share one geometry and use primID
    size_t frames = 0;  // a mesh's first entry in frames_
  };
  // What a mesh hit needs of its triangle besides the vertices: the unit face normal
  // and the rounding bounds of a point interpolated on it. Computed once per
  // triangle (20 B each) rather than per hit: a cross product, a normalise and the
  // vertex extents were a large share of meshSurface, which photon paths call per hit.
  struct TriangleFrame {
    Vec3 ng;
    float error;   // along ng
    float spread;  // in any direction
  };
  static void computeFrames(const TriangleMesh& mesh, TriangleFrame* frames);
  static TriangleFrame frameOf(const Vec3& p0, const Vec3& p1, const Vec3& p2);
  // The invisible boundaries' own Embree scene (geometry/boundary_scene.cpp).
  void buildBoundaries(bool robust);
  // The cut-out rule of mesh `meshIndex` kept in impl_ (null for an opaque material).
  const AlphaCut* alphaCutOf(const Scene& scene, size_t meshIndex, const Vec3& centre);
  SurfaceRecord sphereSurface(const Ray& ray, const Hit& hit, uint8_t fields) const;
  static SurfaceRecord sphereRecord(const Sphere& s, const Ray& ray, float t, uint8_t fields);
  SurfaceRecord meshSurface(const Ray& ray, const Hit& hit, uint8_t fields) const;
  glm::vec4 meshColor(const Hit& hit) const;

  const Scene& scene_;
  std::unique_ptr<Impl> impl_;
  std::vector<GeometryRef> geometries_;  // by Embree geomID
  std::vector<TriangleFrame> frames_;    // every mesh's triangles, mesh after mesh
  std::vector<Vec3> meshCentres_;        // for spherical UVs on meshes without uvs
  std::vector<float> meshRadii_;         // half-diagonal: spherical-uv scale on meshes without uvs
  int packetWidth_ = 1;
  int nativePacketWidth_ = 1;
  bool coloured_ = false;  // some mesh has vertex colours
  SceneSphere bounds_;
};

// The colour at barycentrics (u, v) of triangle `prim` of a mesh with colours,
// clamped to [0, 1]: shading and the cut-out filter read the same value.
glm::vec4 vertexColorAt(const TriangleMesh& mesh, uint32_t prim, float u, float v);

// Equirectangular (u, v) of a unit direction from a centre, y up: u grows
// eastwards with u = 0.5 facing +z, v = 0 at the north pole. u is in [0, 1).
Vec2 sphericalUv(const Vec3& unitDir);
// How fast those (u, v) change per unit of distance on a sphere of this radius.
Vec2 sphericalUvPerWorld(float radius);

}  // namespace penumbra
