// The camera pilot (plan/camera_pilot.h): a 32 x 24 grid of pixel centres, each ray
// followed through mirror reflection and glass (Fresnel reflection and transmission,
// the latter straight on: only the count of surfaces matters) until its weight falls
// below render.min_weight or the depth reaches render.max_depth.
#include "plan/camera_pilot.h"
#include "core/optics.h"
#include "plan/transport_model.h"
#include "trace/camera.h"
#include <algorithm>
#include <cmath>

namespace penumbra {
namespace {

constexpr int kPilotColumns = 32, kPilotRows = 24;

struct Walker {
  const Scene& scene;
  const TraceScene& tracer;
  CameraPilot tally;

  void follow(const Ray& ray, float weight, int depth) {
    Hit hit;
    if (!tracer.intersect(ray, hit)) {
      tally.missesPerSample += 1.0;
      return;
    }
    tally.pointsPerSample += 1.0;
    const SurfaceRecord s = tracer.surface(ray, hit);
    const Material& m = scene.materials[size_t(s.material)];
    const bool mirror = !m.transparent && transportOf(scene).reflects(m, scene.photons);
    if (!m.transparent && maxComponent(m.diffuse) > 0.0f) tally.diffusePerSample += 1.0;
    for (int t : {m.texture, m.emissionTexture, m.metalRoughTexture, m.normalTexture}) tally.texturesPerSample += t >= 0;
    if ((!m.transparent && !mirror) || depth + 1 >= scene.render.maxDepth) return;
    const float kr = m.transparent ? fresnelDielectric(std::abs(glm::dot(ray.dir, s.ns)), 1.0f, m.ior) : m.kr;
    const auto branch = [&](const Vec3& dir, float share) {
      if (weight * share < scene.render.minWeight) return;
      Ray next;
      next.origin = spawnOrigin(s, dir);
      next.dir = dir;
      follow(next, weight * share, depth + 1);
    };
    branch(reflect(ray.dir, s.ns), kr);
    if (m.transparent) branch(ray.dir, 1.0f - kr);
  }
};

}  // namespace

CameraPilot measureCamera(const Scene& scene, const TraceScene& tracer, const PixelBounds& bounds) {
  const CameraRays camera(scene.camera);
  Walker walker{scene, tracer, {}};
  for (int row = 0; row < kPilotRows; ++row) {
    for (int column = 0; column < kPilotColumns; ++column) {
      const float fx = bounds.x0 + (column + 0.5f) * float(bounds.width()) / kPilotColumns;
      const float fy = bounds.y0 + (row + 0.5f) * float(bounds.height()) / kPilotRows;
      walker.follow(camera.generate(fx, fy), 1.0f, 0);
    }
  }
  CameraPilot p = walker.tally;
  const double rays = double(kPilotColumns) * kPilotRows;
  p.pointsPerSample /= rays;
  p.diffusePerSample /= rays;
  p.missesPerSample /= rays;
  p.texturesPerSample /= rays;
  return p;
}

}  // namespace penumbra
