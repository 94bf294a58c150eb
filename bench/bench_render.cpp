// Whole-frame render throughput of the Whitted core (photon maps off) and of the
// full two-pass renderer, at 1 and 2 threads: the speed-up is the figure that
// matters on this 2-core machine (docs/PERFORMANCE.md).
#include "cli/pipeline.h"
#include <benchmark/benchmark.h>
#include <string>

using namespace penumbra;

namespace {

void renderScene(benchmark::State& state, const std::string& scene, std::vector<std::string> overrides) {
  RenderRequest req;
  req.scenePath = std::string(PENUMBRA_SOURCE_DIR) + "/scenes/" + scene;
  req.threads = static_cast<int>(state.range(0));
  req.overrides = std::move(overrides);
  double render = 0.0, total = 0.0;
  int64_t pixels = 0;
  for (auto _ : state) {
    RenderResult r = runRender(req);
    render += r.stats.time.render;
    total += r.stats.time.total;
    pixels += int64_t(r.stats.width) * r.stats.height;
    benchmark::DoNotOptimize(r.image.pixels.data());
  }
  state.counters["render_s"] = benchmark::Counter(render, benchmark::Counter::kAvgIterations);
  state.counters["total_s"] = benchmark::Counter(total, benchmark::Counter::kAvgIterations);
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
// Full renderer with the default 5M-photon shadow map and the gate on.
void BM_GatedShadows(benchmark::State& s) { renderScene(s, "fig03_shadows.json", {}); }

}  // namespace

BENCHMARK(BM_WhittedShadows)->Arg(1)->Arg(2)->Unit(benchmark::kMillisecond)->UseRealTime()->MinTime(2.0);
BENCHMARK(BM_WhittedGlassBox)->Arg(1)->Arg(2)->Unit(benchmark::kMillisecond)->UseRealTime()->MinTime(2.0);
BENCHMARK(BM_WhittedTeapot64)->Arg(1)->Arg(2)->Unit(benchmark::kMillisecond)->UseRealTime()->MinTime(2.0);
BENCHMARK(BM_GatedShadows)->Arg(1)->Arg(2)->Unit(benchmark::kMillisecond)->UseRealTime()->Iterations(3);

BENCHMARK_MAIN();
