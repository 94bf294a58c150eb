// What Embree's robust (watertight) traversal costs and what it buys: camera and
// incoherent rays on the showcase and on the physical Cornell room scaled by 1e4, timed
// interleaved against the default traversal, and the camera rays that slip through
// shared triangle edges (hit with robust, missed without) counted on the scale series.
#include "core/rng.h"
#include "core/sampling.h"
#include "geometry/trace_scene.h"
#include "trace/camera.h"
#include "io/scene_loader.h"
#include "bench/bench_common.h"
#include <benchmark/benchmark.h>
#include <algorithm>
#include <chrono>
#include <cstdio>
#include <memory>
#include <string>
#include <vector>

namespace penumbra {
namespace {

// Every length times s; a point light's intensity times s^2 keeps the image the same.
Scene scaled(Scene scene, float s) {
  scene.camera.position *= s;
  scene.camera.lookAt *= s;
  for (Light& l : scene.lights) {
    l.position *= s;
    l.edge1 *= s;
    l.edge2 *= s;
    l.radius *= s;
    if (l.type == LightType::Point) l.intensity *= s * s;
  }
  for (Sphere& sp : scene.spheres) {
    sp.center *= s;
    sp.radius *= s;
  }
  for (TriangleMesh& m : scene.meshes)
    for (Vec3& p : m.positions) p *= s;
  return scene;
}

std::string scenePath(const char* name) { return std::string(PENUMBRA_SOURCE_DIR) + "/scenes/" + name; }

// Camera rays through every pixel centre, and one cosine bounce from each first hit.
struct Rays {
  std::vector<Ray> camera, bounce;
};
Rays makeRays(const Scene& scene, const TraceScene& tracer) {
  Rays rays;
  const CameraRays cam(scene.camera);
  Rng rng(0x5eed);
  for (int y = 0; y < scene.camera.height; ++y)
    for (int x = 0; x < scene.camera.width; ++x) {
      Ray ray = cam.generate(x + 0.5f, y + 0.5f);
      rays.camera.push_back(ray);
      Hit hit;
      if (!tracer.intersect(ray, hit)) continue;
      const SurfaceRecord s = tracer.surface(ray, hit, kSurfaceGeometric);
      const Vec3 dir = toWorld(cosineHemisphere(rng.uniform(), rng.uniform()), s.ng);
      rays.bounce.push_back(Ray{spawnOrigin(s, dir), dir});
    }
  return rays;
}

size_t hits(const TraceScene& tracer, const std::vector<Ray>& rays) {
  size_t n = 0;
  for (const Ray& r : rays) {
    Hit h;
    n += tracer.intersect(r, h) ? 1 : 0;
  }
  return n;
}

// Both traversals of one scene, timed back to back; each keeps its fastest pass.
void timeBoth(benchmark::State& state, const Scene& scene) {
  const TraceScene fast(scene, false), robust(scene, true);
  const Rays rays = makeRays(scene, robust);
  double best[2][2] = {{1e30, 1e30}, {1e30, 1e30}};  // [robust][camera, bounce]
  for (auto _ : state) {
    for (int r = 0; r < 2; ++r) {
      const TraceScene& t = r ? robust : fast;
      for (int k = 0; k < 2; ++k) {
        const std::vector<Ray>& v = k ? rays.bounce : rays.camera;
        const auto t0 = std::chrono::steady_clock::now();
        benchmark::DoNotOptimize(hits(t, v));
        const std::chrono::duration<double, std::nano> dt = std::chrono::steady_clock::now() - t0;
        best[r][k] = std::min(best[r][k], dt.count() / double(v.size()));
      }
    }
  }
  state.counters["camera_fast_ns"] = best[0][0];
  state.counters["camera_robust_ns"] = best[1][0];
  state.counters["bounce_fast_ns"] = best[0][1];
  state.counters["bounce_robust_ns"] = best[1][1];
  state.counters["camera_ratio"] = best[1][0] / best[0][0];
  state.counters["bounce_ratio"] = best[1][1] / best[0][1];
}

void BM_RobustShowcase(benchmark::State& state) { timeBoth(state, loadScene(scenePath("showcase.json"))); }

void BM_RobustCornell1e4(benchmark::State& state) {
  timeBoth(state, scaled(loadScene(scenePath("cornell_physical.json")), 1e4f));
}

// Holes: camera rays into the closed-on-five-sides room that the default traversal loses
// between two triangles of one wall, at 512x512, per scale.
void BM_EdgeHoles(benchmark::State& state) {
  const float s = std::pow(10.0f, static_cast<float>(state.range(0)));
  const Scene scene = scaled(loadScene(scenePath("cornell_physical.json")), s);
  const TraceScene fast(scene, false), robust(scene, true);
  const Rays rays = makeRays(scene, robust);
  size_t lost = 0;
  for (auto _ : state) lost = hits(robust, rays.camera) - hits(fast, rays.camera);
  state.counters["holes_fast"] = static_cast<double>(lost);
  state.counters["rays"] = static_cast<double>(rays.camera.size());
}

}  // namespace
}  // namespace penumbra

using namespace penumbra;
BENCHMARK(BM_RobustShowcase)->Unit(benchmark::kMillisecond)->UseRealTime()->Iterations(5);
BENCHMARK(BM_RobustCornell1e4)->Unit(benchmark::kMillisecond)->UseRealTime()->Iterations(5);
BENCHMARK(BM_EdgeHoles)->DenseRange(-5, 6, 1)->Unit(benchmark::kMillisecond)->Iterations(1);
PENUMBRA_BENCHMARK_MAIN()
