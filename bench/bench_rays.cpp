// Embree ray throughput (rtcIntersect1 / rtcOccluded1 through TraceScene) on the scenes
// the whole-render benchmarks use: camera, shadow and incoherent rays, 1 and 2 threads.
// These are the raw rates docs/PERFORMANCE.md compares the renders against.
#include "bench/bench_common.h"
#include "io/scene_loader.h"
#include <benchmark/benchmark.h>
#include <map>
#include <memory>

namespace penumbra::bench {
namespace {

struct SceneRays {
  Scene scene;
  TraceScene tracer;
  RaySets rays;
  explicit SceneRays(const std::string& name)
      : scene(loadScene(scenePath(name))), tracer(scene), rays(makeRaySets(scene, tracer)) {}
};

// Built once per scene and kept: the benchmarks of one scene run back to back.
const SceneRays& sceneRays(const std::string& name) {
  static std::map<std::string, std::unique_ptr<SceneRays>> cache;
  auto& slot = cache[name];
  if (!slot) slot = std::make_unique<SceneRays>(name);
  return *slot;
}

enum Kind { kCamera, kShadow, kIncoherent };

void BM_Rays(benchmark::State& state, const std::string& scene, Kind kind) {
  const SceneRays& s = sceneRays(scene);
  const std::vector<Ray>& rays =
      kind == kCamera ? s.rays.camera : kind == kShadow ? s.rays.shadow : s.rays.incoherent;
  tbb::global_control limit(tbb::global_control::max_allowed_parallelism, state.range(0));
  size_t hits = 0;
  const CpuShare cpu;
  for (auto _ : state) hits = tracePass(s.tracer, rays, kind == kShadow);
  cpu.report(state, static_cast<int>(state.range(0)));
  state.SetItemsProcessed(static_cast<int64_t>(state.iterations() * rays.size()));
  state.counters["rays"] = double(rays.size());
  state.counters["hit_fraction"] = rays.empty() ? 0.0 : double(hits) / double(rays.size());
  // Seconds of wall time per ray (the console shows it with an SI prefix, "55n" = 55 ns).
  state.counters["time_per_ray"] = benchmark::Counter(
      double(state.iterations() * rays.size()), benchmark::Counter::kIsRate | benchmark::Counter::kInvert);
}

void registerAll() {
  const char* scenes[][2] = {{"fig07_glass_in_box.json", "glass_box"},
                             {"showcase.json", "showcase"},
                             {"cornell_physical.json", "cornell_physical"}};
  const std::pair<Kind, const char*> kinds[] = {
      {kCamera, "camera"}, {kShadow, "shadow"}, {kIncoherent, "incoherent"}};
  for (const auto& sc : scenes)
    for (const auto& [kind, kname] : kinds) {
      const std::string name = std::string("Rays/") + sc[1] + "/" + kname;
      const std::string file = sc[0];
      const Kind k = kind;
      benchmark::RegisterBenchmark(name.c_str(),
                                   [file, k](benchmark::State& st) { BM_Rays(st, file, k); })
          ->ArgName("threads")->Arg(1)->Arg(2)
          ->MinTime(0.1)->UseRealTime()->Unit(benchmark::kMillisecond);
    }
}

}  // namespace
}  // namespace penumbra::bench

int main(int argc, char** argv) {
  penumbra::bench::registerAll();
  return penumbra::bench::benchmarkMain(argc, argv);
}
