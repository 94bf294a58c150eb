// The media cost model: how much of the image sees a medium (its bounding spheres'
// share of the view), how thick each medium is over its extent, and the per-operation
// times of plan/cost_model.h.
#include "plan/media_estimate.h"
#include "plan/cost_model.h"
#include "core/media/density_grid.h"
#include "gather/volume_map.h"
#include "io/scene_defaults.h"
#include <nlohmann/json.hpp>
#include <algorithm>
#include <cmath>

namespace penumbra {
namespace {

using namespace cost;

struct Bound {
  Vec3 center{0.0f};
  float radius = 0.0f;
};

Bound boundOf(const std::vector<Vec3>& points) {
  if (points.empty()) return {};
  SceneBounds b;
  for (const Vec3& p : points) b.add(p);
  return {0.5f * (b.lo + b.hi), 0.5f * glm::length(b.hi - b.lo)};
}

// Every object's bounding sphere whose inside is medium `m` (spheres and meshes,
// with a material or as invisible boundaries).
std::vector<Bound> boundsOf(const Scene& scene, int m) {
  std::vector<Bound> out;
  for (const auto* list : {&scene.spheres, &scene.boundarySpheres}) {
    for (const Sphere& s : *list) if (s.media.inside == m) out.push_back({s.center, s.radius});
  }
  for (const auto* list : {&scene.meshes, &scene.boundaryMeshes}) {
    for (const TriangleMesh& mesh : *list) if (mesh.media.inside == m) out.push_back(boundOf(mesh.positions));
  }
  return out;
}

// The whole scene's extent: a medium filling it is crossed over about this length.
float sceneExtent(const Scene& scene) {
  SceneBounds b = sceneBounds(scene);  // every mesh vertex and sphere
  b.add(scene.camera.position);
  for (const Light& l : scene.lights) b.add(l.position);
  return glm::length(b.hi - b.lo);
}

// The share of the view a sphere covers: its disc's solid angle over the frame's
// (1 where the camera is inside it).
double viewShare(const Scene& scene, const Bound& b) {
  const Camera& c = scene.camera;
  const float d = glm::length(b.center - c.position);
  if (d <= b.radius) return 1.0;
  const double aspect = double(c.width) / std::max(1, c.height);
  if (c.orthoHeight > 0.0f) return std::min(1.0, kPi * b.radius * b.radius / (c.orthoHeight * c.orthoHeight * aspect));
  const double halfY = std::tan(0.5 * double(c.fovY) * kPi / 180.0);
  const double t = std::tan(std::asin(std::min(1.0, double(b.radius) / d)));
  return std::min(1.0, kPi * t * t / (4.0 * halfY * halfY * aspect));
}

}  // namespace

MediaCost mediaCost(const Scene& scene, double volumeStoredPerPass) {
  MediaCost m;
  if (!scene.hasMedia()) return m;
  m.any = true;
  const PhotonSettings& ps = scene.photons;
  const bool filled = scene.sceneMedium != kNoMedium || scene.cameraMedium != kNoMedium;
  const float extent = sceneExtent(scene);
  double steps = 0.0, scatterDepth = 0.0;
  for (size_t i = 0; i < scene.media.size(); ++i) {
    const Medium& medium = scene.media[i];
    const bool fills = scene.sceneMedium == int(i);
    double length = fills ? extent : 0.0, share = fills ? 1.0 : 0.0;
    for (const Bound& b : boundsOf(scene, int(i))) {
      length = std::max(length, 2.0 * b.radius);
      share += viewShare(scene, b);
    }
    if (!filled) m.cameraShare = std::min(1.0, m.cameraShare + share);
    // A grid is tracked against its majorant: about sigma_t x majorant x length steps a crossing.
    const double majorant = medium.density ? medium.density->maxDensity : 1.0;
    if (medium.density) steps += maxComponent(medium.sigmaT()) * majorant * length;
    // Scatter events along one crossing, at most one per bounce a photon may take.
    scatterDepth = std::max(scatterDepth, double(maxComponent(medium.sigmaS)) * majorant * length);
  }
  if (filled) m.cameraShare = 1.0;
  // A photon crosses a medium once per flight and scatters at most once per bounce.
  m.storesPerPhoton = std::min<double>(ps.maxBounces, scatterDepth * (1.0 + ps.maxBounces));
  m.photonEventNs = kMediumEventNs + steps * kTrackingStepNs;
  // Per light, volume_samples times: an equiangular and a distance sample, each with a
  // transmittance ray.
  double samples = 0.0;
  for (const Light& l : scene.lights) samples += maxComponent(l.radiance()) > 0.0f ? scene.render.volumeSamples : 0.0;
  m.sampleNs = samples * 2.0 * (kMediumSampleNs + kRayNs);
  m.trackingNs = steps * kTrackingStepNs * (1.0 + 2.0 * samples);
  // A beam walks about sqrt(pi N / kCellPhotons) cells of N photons' grid (its cell is
  // the radius of a kCellPhotons beam) and finds about k photons each pass.
  if (volumeStoredPerPass > 0.0) {
    const double cells = std::sqrt(kPi * volumeStoredPerPass / VolumePhotonMap::kCellPhotons);
    m.gatherNs = cells * kVolumeGatherNsPerCell + ps.kVolume * kVolumeGatherNsPerNeighbour;
  }
  return m;
}

nlohmann::json mediaCostJson(const MediaCost& m, double cameraSeconds, double photonSeconds) {
  return {{"camera_share", m.cameraShare},
          {"ns_per_camera_ray", {{"samples", m.sampleNs}, {"tracking", m.trackingNs}, {"volume_gather", m.gatherNs}}},
          {"volume_stores_per_photon", m.storesPerPhoton},
          {"seconds", {{"camera", cameraSeconds}, {"photons", photonSeconds}}}};
}

}  // namespace penumbra
