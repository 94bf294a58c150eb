// Whole renders through runRender at 1 and 2 threads: the Whitted core (photon maps
// off) and three scenes at their own settings, with per-stage times (stats.time.*)
// and ray/gather counts as counters for `make scaling` and docs/PERFORMANCE.md; and
// a compute-only control that measures the machine's own 2T/1T in the same run.
#include "bench/bench_common.h"
#include "cli/bench/compute_control.h"
#include "plan/pipeline.h"
#include <benchmark/benchmark.h>
#include <tbb/global_control.h>
#include <string>

using namespace penumbra;

namespace {

void renderScene(benchmark::State& state, const std::string& scene, std::vector<std::string> overrides) {
  RenderRequest req;
  req.scenePath = std::string(PENUMBRA_SOURCE_DIR) + "/scenes/" + scene;
  req.session.threads = static_cast<int>(state.range(0));
  req.overrides = std::move(overrides);
  Timings sum;
  RayCounts rays;  // of the last frame (every frame casts the same)
  int64_t pixels = 0;
  const penumbra::bench::CpuShare cpu;
  for (auto _ : state) {
    RenderResult r = runRender(req);
    const Timings& t = r.stats.time;
    sum.load += t.load; sum.buildBvh += t.buildBvh; sum.emit += t.emit;
    sum.buildMaps += t.buildMaps; sum.precompute += t.precompute; sum.render += t.render;
    sum.total += t.total;
    rays = r.stats.rays;
    pixels += int64_t(r.stats.width) * r.stats.height;
    benchmark::DoNotOptimize(r.image.pixels.data());
  }
  cpu.report(state, req.session.threads);
  auto avg = [&](const char* name, double v) {
    state.counters[name] = benchmark::Counter(v, benchmark::Counter::kAvgIterations);
  };
  avg("load_s", sum.load + sum.buildBvh);  // scene, meshes and the Embree BVH
  avg("emit_s", sum.emit);
  avg("maps_s", sum.buildMaps);
  avg("precompute_s", sum.precompute);
  avg("render_s", sum.render);
  avg("total_s", sum.total);
  state.counters["camera_rays"] = double(rays.camera);
  state.counters["shadow_rays"] = double(rays.shadow);
  state.counters["secondary_rays"] = double(rays.reflection + rays.refraction);
  state.counters["gathers"] = double(rays.gatherQueries);
  state.counters["gate_queries"] = double(rays.gateQueries);
  state.counters["cache_lookups"] = double(rays.cacheLookups);
  state.SetItemsProcessed(pixels);
}

// Whitted core only: every shadow test is a ray.
void BM_WhittedShadows(benchmark::State& s) { renderScene(s, "fig03_shadows.json", {"photons.shadow=0"}); }
void BM_WhittedGlassBox(benchmark::State& s) { renderScene(s, "fig07_glass_in_box.json", {"photons.shadow=0"}); }
// The reflective teapot at subdivisions 64 (262k triangles), Whitted only: a
// mesh-heavy frame; total_s includes tessellating the teapot on load.
void BM_WhittedTeapot64(benchmark::State& s) {
  renderScene(s, "fig05_reflective_mesh.json", {"photons.shadow=0", "objects[1].subdivisions=64"});
}
// fig03 at its own settings (5M shadow photons; photons.gate auto decides).
void BM_GatedShadows(benchmark::State& s) { renderScene(s, "fig03_shadows.json", {}); }

// The three whole-render scenes of the suite (docs/PERFORMANCE.md, "Benchmark suite"):
// a Whitted glass box (rays only), the showcase (both photon maps, precomputed lookups)
// and the physical Cornell room at 1 spp (exact caustic and global gathers).
void BM_SceneGlassBox(benchmark::State& s) { renderScene(s, "fig07_glass_in_box.json", {}); }
void BM_SceneShowcase(benchmark::State& s) { renderScene(s, "showcase.json", {}); }
void BM_SceneCornellPhysical(benchmark::State& s) {
  renderScene(s, "cornell_physical.json", {"camera.spp=1"});
}

// The machine's own ceiling for the scaling table (cli/bench/compute_control.h), the same
// work `penumbra bench` measures beside the user's scenes.
void BM_ControlCompute(benchmark::State& state) {
  const int threads = static_cast<int>(state.range(0));
  tbb::global_control limit(tbb::global_control::max_allowed_parallelism, threads);
  const penumbra::bench::CpuShare cpu;
  for (auto _ : state) benchmark::DoNotOptimize(computeControl());
  cpu.report(state, threads);
}

}  // namespace

BENCHMARK(BM_ControlCompute)->ArgName("threads")->Arg(1)->Arg(2)->Unit(benchmark::kMillisecond)
    ->UseRealTime()->MinTime(0.5);
BENCHMARK(BM_WhittedShadows)->Arg(1)->Arg(2)->Unit(benchmark::kMillisecond)->UseRealTime()->MinTime(2.0);
BENCHMARK(BM_WhittedGlassBox)->Arg(1)->Arg(2)->Unit(benchmark::kMillisecond)->UseRealTime()->MinTime(2.0);
BENCHMARK(BM_WhittedTeapot64)->Arg(1)->Arg(2)->Unit(benchmark::kMillisecond)->UseRealTime()->MinTime(2.0);
BENCHMARK(BM_GatedShadows)->Arg(1)->Arg(2)->Unit(benchmark::kMillisecond)->UseRealTime()->Iterations(3);
// One frame per repetition for the long ones: `make bench` asks for 3 repetitions,
// 1- and 2-thread runs interleaved, so drift on the shared machine hits both alike.
BENCHMARK(BM_SceneGlassBox)->ArgName("threads")->Arg(1)->Arg(2)->Unit(benchmark::kMillisecond)
    ->UseRealTime()->MinTime(0.5);
BENCHMARK(BM_SceneShowcase)->ArgName("threads")->Arg(1)->Arg(2)->Unit(benchmark::kMillisecond)
    ->UseRealTime()->Iterations(1);
BENCHMARK(BM_SceneCornellPhysical)->ArgName("threads")->Arg(1)->Arg(2)->Unit(benchmark::kMillisecond)
    ->UseRealTime()->Iterations(1);

PENUMBRA_BENCHMARK_MAIN()
