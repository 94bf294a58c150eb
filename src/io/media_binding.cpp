// Media bound to the scene's solids: every closed object is a solid whose inside holds
// its medium (or vacuum); a point's medium is the inside of the smallest solid holding it.
#include "io/media_binding.h"

#include "core/light_sample.h"
#include "io/closed_mesh.h"

#include <limits>
#include <optional>
#include <vector>

namespace penumbra {

namespace {

// A closed object as a container: its inside medium, size and a point on or in it.
struct Solid {
  const Sphere* sphere = nullptr;
  const TriangleMesh* mesh = nullptr;
  int inside = kNoMedium;
  double volume = 0.0;
  Vec3 lo{0.0f}, hi{0.0f};  // bounds, to skip the mesh test for points far away
  Vec3 probe{0.0f};         // tested against other solids to find what encloses this one

  bool contains(const Vec3& p) const {
    if (sphere) {
      const glm::dvec3 d = glm::dvec3(p) - glm::dvec3(sphere->center);
      return glm::dot(d, d) < double(sphere->radius) * double(sphere->radius);
    }
    if (glm::any(glm::lessThan(p, lo)) || glm::any(glm::greaterThan(p, hi))) return false;
    return meshContains(*mesh, p);
  }
};

Solid sphereSolid(const Sphere& s) {
  Solid out;
  out.sphere = &s;
  out.inside = s.media.inside;
  const double r = s.radius;
  out.volume = 4.0 / 3.0 * 3.14159265358979323846 * r * r * r;
  out.probe = s.center;
  return out;
}

Solid meshSolid(const TriangleMesh& m) {
  Solid out;
  out.mesh = &m;
  out.inside = m.media.inside;
  out.volume = enclosedVolume(m);
  out.lo = out.hi = m.triangles.empty() ? Vec3(0.0f) : m.positions[m.triangles[0][0]];
  for (const auto& tri : m.triangles) {
    for (uint32_t v : tri) {
      out.lo = glm::min(out.lo, m.positions[v]);
      out.hi = glm::max(out.hi, m.positions[v]);
    }
  }
  // The centroid of the largest triangle: on the surface, so inside whatever holds the
  // whole mesh even when the mesh is not convex.
  double best = -1.0;
  for (const auto& tri : m.triangles) {
    const Vec3 a = m.positions[tri[0]], b = m.positions[tri[1]], c = m.positions[tri[2]];
    const double area = glm::length(glm::cross(glm::dvec3(b - a), glm::dvec3(c - a)));
    if (area > best) best = area, out.probe = (a + b + c) / 3.0f;
  }
  return out;
}

class MediumLocator {
 public:
  MediumLocator(std::vector<Solid> solids, int sceneMedium) : solids_(std::move(solids)), scene_(sceneMedium) {}

  // The inside of the smallest solid holding p and larger than `above` (an object's own
  // volume, so it is never its own outside).
  int at(const Vec3& p, double above = -1.0) const {
    const Solid* best = nullptr;
    for (const Solid& s : solids_) {
      if (s.volume <= above || (best && s.volume >= best->volume)) continue;
      if (s.contains(p)) best = &s;
    }
    return best ? best->inside : scene_;
  }

 private:
  std::vector<Solid> solids_;
  int scene_;
};

bool isEmitter(const Scene& scene, int material) {
  return material >= 0 && size_t(material) < scene.materials.size() && scene.materials[material].light >= 0;
}

// Where a light's photons start; light from a direction or from infinity comes from
// outside. An area light's centre: its bounds' for a mesh, position + (edge1 + edge2) / 2
// otherwise (a quad's middle; spheres and disks have no edges, so their centre).
std::optional<Vec3> lightPoint(const Light& light) {
  const LightSupport support = lightTraits(light).support;
  if (support == LightSupport::Direction || support == LightSupport::Infinite) return std::nullopt;
  if (light.triangles.empty()) return light.position + 0.5f * (light.edge1 + light.edge2);
  Vec3 lo(std::numeric_limits<float>::max()), hi(-std::numeric_limits<float>::max());
  for (const Vec3& p : light.triangles) lo = glm::min(lo, p), hi = glm::max(hi, p);
  return 0.5f * (lo + hi);
}

}  // namespace

void bindMedia(Scene& scene) {
  if (!scene.hasMedia()) return;
  // Which meshes are closed, once: a surface list and the boundary list.
  auto closedFlags = [](const SharedList<TriangleMesh>& meshes) {
    std::vector<bool> closed;
    for (const TriangleMesh& m : meshes) closed.push_back(!m.triangles.empty() && openEdgeCount(m) == 0);
    return closed;
  };
  const std::vector<bool> closedSurfaces = closedFlags(scene.meshes), closedBoundaries = closedFlags(scene.boundaryMeshes);
  // Light surfaces hold nothing: a sphere light's centre is not in vacuum.
  std::vector<Solid> solids;
  for (const Sphere& s : scene.spheres) {
    if (!isEmitter(scene, s.material)) solids.push_back(sphereSolid(s));
  }
  for (const Sphere& s : scene.boundarySpheres) solids.push_back(sphereSolid(s));
  for (size_t i = 0; i < scene.meshes.size(); ++i) {
    if (closedSurfaces[i] && !isEmitter(scene, scene.meshes[i].material)) solids.push_back(meshSolid(scene.meshes[i]));
  }
  for (size_t i = 0; i < scene.boundaryMeshes.size(); ++i) {
    if (closedBoundaries[i]) solids.push_back(meshSolid(scene.boundaryMeshes[i]));
  }
  const MediumLocator locate(std::move(solids), scene.sceneMedium);

  // Each object's outside: the smallest larger solid holding its probe point.
  auto outsideOf = [&](const Solid& own) { return locate.at(own.probe, own.volume); };
  auto bindSphere = [&](Sphere& s) {
    const Solid own = sphereSolid(s);
    s.media = {s.media.inside, outsideOf(own), true};
  };
  auto bindMesh = [&](TriangleMesh& m, bool closed) {
    if (!closed) {
      const int around = locate.at(meshSolid(m).probe);
      m.media = {around, around, false};
      return;
    }
    const Solid own = meshSolid(m);
    m.media = {m.media.inside, outsideOf(own), true, signedVolume(m) < 0.0};
  };
  for (Sphere& s : scene.spheres) bindSphere(s);
  for (Sphere& s : scene.boundarySpheres) bindSphere(s);
  for (size_t i = 0; i < scene.meshes.size(); ++i) bindMesh(scene.meshes[i], closedSurfaces[i]);
  for (size_t i = 0; i < scene.boundaryMeshes.size(); ++i) bindMesh(scene.boundaryMeshes[i], closedBoundaries[i]);

  scene.cameraMedium = locate.at(scene.camera.position);
  for (Light& light : scene.lights) {
    const std::optional<Vec3> p = lightPoint(light);
    light.medium = p ? locate.at(*p) : scene.sceneMedium;
  }
}

}  // namespace penumbra
