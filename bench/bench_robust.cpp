// What Embree's traversal options cost. Robust (watertight) traversal: rays on the
// showcase and on the physical Cornell room scaled by 1e4, timed interleaved against
// the default traversal, and the camera rays that slip through shared triangle edges
// (hit with robust, missed without) counted on the scale series. Compact leaves: the
// same rays against the default layout (bench_load measures the memory they save).
#include "bench/bench_common.h"
#include "geometry/trace_scene.h"
#include "io/scene_loader.h"
#include <benchmark/benchmark.h>
#include <algorithm>
#include <chrono>
#include <cmath>
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

size_t hits(const TraceScene& tracer, const std::vector<Ray>& rays) {
  size_t n = 0;
  for (const Ray& r : rays) {
    Hit h;
    n += tracer.intersect(r, h) ? 1 : 0;
  }
  return n;
}

// Camera rays as the tile loop sends them: packets of 256 in scan-line order.
size_t packetHits(const TraceScene& tracer, const std::vector<Ray>& rays) {
  std::vector<Hit> out(256);
  size_t n = 0;
  for (size_t i = 0; i < rays.size(); i += 256) {
    const int count = static_cast<int>(std::min<size_t>(256, rays.size() - i));
    tracer.intersectPacket(rays.data() + i, count, out.data());
    for (int k = 0; k < count; ++k) n += out[k].valid() ? 1 : 0;
  }
  return n;
}

size_t blocked(const TraceScene& tracer, const std::vector<Ray>& rays) {
  size_t n = 0;
  for (const Ray& r : rays) n += tracer.occluded(r) ? 1 : 0;
  return n;
}

// Two tracers of one scene on the same rays (camera rays one by one and as packets,
// one cosine bounce from each first hit, shadow rays to the lights), timed back to
// back on one thread; each keeps its fastest pass. Counters: KIND_NAME_ns per ray and
// KIND_ratio, `second` over `first`.
void timeBoth(benchmark::State& state, const Scene& scene, const TraceScene& first, const TraceScene& second,
              const char* firstName, const char* secondName) {
  const bench::RaySets rays = bench::makeRaySets(scene, second);
  const char* kinds[] = {"camera", "packet", "bounce", "shadow"};
  double best[2][4];
  std::fill(&best[0][0], &best[0][0] + 8, 1e30);
  for (auto _ : state) {
    for (int r = 0; r < 2; ++r) {
      const TraceScene& t = r ? second : first;
      for (int k = 0; k < 4; ++k) {
        const std::vector<Ray>& v = k == 2 ? rays.incoherent : k == 3 ? rays.shadow : rays.camera;
        const auto t0 = std::chrono::steady_clock::now();
        benchmark::DoNotOptimize(k == 1 ? packetHits(t, v) : k == 3 ? blocked(t, v) : hits(t, v));
        const std::chrono::duration<double, std::nano> dt = std::chrono::steady_clock::now() - t0;
        best[r][k] = std::min(best[r][k], dt.count() / double(std::max<size_t>(1, v.size())));
      }
    }
  }
  for (int k = 0; k < 4; ++k) {
    state.counters[std::string(kinds[k]) + "_" + firstName + "_ns"] = best[0][k];
    state.counters[std::string(kinds[k]) + "_" + secondName + "_ns"] = best[1][k];
    state.counters[std::string(kinds[k]) + "_ratio"] = best[1][k] / best[0][k];
  }
}

void timeRobust(benchmark::State& state, const Scene& scene) {
  const TraceScene fast(scene, false), robust(scene, true);
  timeBoth(state, scene, fast, robust, "fast", "robust");
}

void BM_RobustShowcase(benchmark::State& state) { timeRobust(state, loadScene(bench::scenePath("showcase.json"))); }

void BM_RobustCornell1e4(benchmark::State& state) {
  timeRobust(state, scaled(loadScene(bench::scenePath("cornell_physical.json")), 1e4f));
}

// Compact leaves (indices into the meshes' vertices) against the default layout, both
// robust: a small scene, and teapot_1m's 1.05M triangles, past kCompactBvhTriangles.
void timeCompact(benchmark::State& state, const char* file) {
  const Scene scene = loadScene(bench::scenePath(file));
  const TraceScene fast(scene, true, BvhLayout::Fast), compact(scene, true, BvhLayout::Compact);
  timeBoth(state, scene, fast, compact, "default", "compact");
}

void BM_CompactShowcase(benchmark::State& state) { timeCompact(state, "showcase.json"); }
void BM_CompactTeapot1M(benchmark::State& state) { timeCompact(state, "teapot_1m.json"); }

// Holes: camera rays into the closed-on-five-sides room that the default traversal loses
// between two triangles of one wall, at 512x512, per scale.
void BM_EdgeHoles(benchmark::State& state) {
  const float s = std::pow(10.0f, static_cast<float>(state.range(0)));
  const Scene scene = scaled(loadScene(bench::scenePath("cornell_physical.json")), s);
  const TraceScene fast(scene, false), robust(scene, true);
  const bench::RaySets rays = bench::makeRaySets(scene, robust);
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
BENCHMARK(BM_CompactShowcase)->Unit(benchmark::kMillisecond)->UseRealTime()->Iterations(5);
BENCHMARK(BM_CompactTeapot1M)->Unit(benchmark::kMillisecond)->UseRealTime()->Iterations(5);
BENCHMARK(BM_EdgeHoles)->DenseRange(-5, 6, 1)->Unit(benchmark::kMillisecond)->Iterations(1);
PENUMBRA_BENCHMARK_MAIN()
