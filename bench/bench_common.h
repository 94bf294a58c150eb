// What the benchmark executables share: main() with our build type and the load in the
// JSON context, CpuShare (contended or slow?), and one scene's camera, shadow and
// incoherent rays and first-hit points (bench_rays, profile_render).
#pragma once
#include "core/cpu_time.h"
#include "core/rng.h"
#include "core/sampling.h"
#include "geometry/trace_scene.h"
#include "trace/camera.h"
#include <tbb/blocked_range.h>
#include <tbb/global_control.h>
#include <tbb/parallel_for.h>
#include <benchmark/benchmark.h>
#include <algorithm>
#include <atomic>
#include <chrono>
#include <fstream>
#include <string>
#include <vector>

namespace penumbra::bench {

// The process's CPU time over (wall time x threads) between construction and report():
// ~1 when every worker had its core, well below 1 when other work on the shared machine
// took them (the 2-thread figure is then a measure of the load, not of the scaling).
class CpuShare {
 public:
  void report(benchmark::State& state, int threads) const { state.counters["cpu_share"] = span_.timing(threads).share; }

 private:
  CpuSpan span_;
};

inline int benchmarkMain(int argc, char** argv) {
  benchmark::AddCustomContext("penumbra_build_type", PENUMBRA_BUILD_TYPE);
  std::string load;
  std::getline(std::ifstream("/proc/loadavg"), load);
  benchmark::AddCustomContext("loadavg_at_start", load);
  benchmark::Initialize(&argc, argv);
  if (benchmark::ReportUnrecognizedArguments(argc, argv)) return 1;
  benchmark::RunSpecifiedBenchmarks();
  benchmark::Shutdown();
  return 0;
}

inline std::string scenePath(const std::string& name) {
  return std::string(PENUMBRA_SOURCE_DIR) + "/scenes/" + name;
}

struct RaySets {
  std::vector<Ray> camera, shadow, incoherent;
  std::vector<Vec3> points;  // first hits, scan-line order (for photon-map queries)
};

// Shadow rays stop just short of the light as light_visibility.cpp's do (a point
// light; an area light is aimed at its centre, a directional light is skipped).
inline RaySets makeRaySets(const Scene& scene, const TraceScene& tracer) {
  RaySets s;
  const CameraRays cam(scene.camera);
  Rng rng(0x5eed);
  for (int y = 0; y < scene.camera.height; ++y)
    for (int x = 0; x < scene.camera.width; ++x) {
      const Ray ray = cam.generate(x + 0.5f, y + 0.5f);
      s.camera.push_back(ray);
      Hit hit;
      if (!tracer.intersect(ray, hit)) continue;
      const SurfaceRecord rec = tracer.surface(ray, hit, kSurfaceGeometric);
      s.points.push_back(rec.position);
      for (const Light& light : scene.lights) {
        if (light.type == LightType::Directional) continue;
        const Vec3 d = light.position - rec.position;
        const float dist = glm::length(d);
        if (!(dist > 0.0f)) continue;
        const Vec3 dir = d / dist;
        if (glm::dot(rec.ng, dir) <= 0.0f) continue;  // behind: the renderer casts nothing
        Ray r{spawnOrigin(rec, dir), dir};
        r.tMax = dist * (1.0f - kShadowRayShortening);
        s.shadow.push_back(r);
      }
      const Vec3 dir = toWorld(cosineHemisphere(rng.uniform(), rng.uniform()), rec.ng);
      s.incoherent.push_back(Ray{spawnOrigin(rec, dir), dir});
    }
  return s;
}

// One pass over `rays` with `threads` workers in blocks of 256 (scan-line order kept
// inside a block); returns the hits, so the optimiser keeps the calls.
inline size_t tracePass(const TraceScene& tracer, const std::vector<Ray>& rays, bool shadow) {
  std::atomic<size_t> hits{0};
  tbb::parallel_for(tbb::blocked_range<size_t>(0, rays.size(), 256), [&](const auto& r) {
    size_t n = 0;
    for (size_t i = r.begin(); i != r.end(); ++i) {
      if (shadow) {
        n += tracer.occluded(rays[i]) ? 1 : 0;
      } else {
        Hit h;
        n += tracer.intersect(rays[i], h) ? 1 : 0;
      }
    }
    hits += n;
  });
  return hits;
}

// Nanoseconds per ray, the fastest of `passes` passes (the machine is shared).
inline double nsPerRay(const TraceScene& tracer, const std::vector<Ray>& rays, bool shadow,
                       int threads, int passes = 5) {
  if (rays.empty()) return 0.0;
  tbb::global_control limit(tbb::global_control::max_allowed_parallelism, threads);
  double best = 1e30;
  for (int p = 0; p < passes; ++p) {
    const auto t0 = std::chrono::steady_clock::now();
    tracePass(tracer, rays, shadow);
    const std::chrono::duration<double, std::nano> dt = std::chrono::steady_clock::now() - t0;
    best = std::min(best, dt.count() / double(rays.size()));
  }
  return best;
}

}  // namespace penumbra::bench

#define PENUMBRA_BENCHMARK_MAIN() \
  int main(int argc, char** argv) { return penumbra::bench::benchmarkMain(argc, argv); }
