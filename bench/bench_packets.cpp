// Camera rays as Embree packets versus single rays on the 1M-triangle teapot
// (scenes/teapot_1m.json): the primary-ray stage alone in Mrays/s, then the whole
// depth view and direct-light-only render, at 1 and 2 threads (docs/PERFORMANCE.md).
#include "plan/pipeline.h"
#include "geometry/trace_scene.h"
#include "trace/camera.h"
#include "io/scene_loader.h"
#include <benchmark/benchmark.h>
#include <tbb/parallel_for.h>
#include <tbb/task_arena.h>
#include <memory>
#include <string>
#include <vector>

using namespace penumbra;

namespace {

const std::string kScene = std::string(PENUMBRA_SOURCE_DIR) + "/scenes/teapot_1m.json";

// The scene, its BVH and one frame's camera rays in the renderer's order: 16x16
// tiles, 4x4 blocks inside a tile, pixel centres. Built once for all runs.
struct PrimaryStage {
  Scene scene;
  std::unique_ptr<TraceScene> tracer;
  std::vector<Ray> rays;  // tile after tile
  std::vector<int> tileStart;
  PrimaryStage() : scene(loadScene(kScene)) {
    tracer = std::make_unique<TraceScene>(scene);
    const Camera& cam = scene.camera;
    CameraRays camera(cam);
    for (int ty = 0; ty < cam.height; ty += 16) {
      for (int tx = 0; tx < cam.width; tx += 16) {
        tileStart.push_back(static_cast<int>(rays.size()));
        const int x1 = std::min(tx + 16, cam.width), y1 = std::min(ty + 16, cam.height);
        for (int by = ty; by < y1; by += 4)
          for (int bx = tx; bx < x1; bx += 4)
            for (int y = by; y < std::min(by + 4, y1); ++y)
              for (int x = bx; x < std::min(bx + 4, x1); ++x) rays.push_back(camera.generate(x + 0.5f, y + 0.5f));
      }
    }
    tileStart.push_back(static_cast<int>(rays.size()));
  }
};

PrimaryStage& stage() {
  static PrimaryStage s;
  return s;
}

// range(0): threads; range(1): packet width (1 = rtcIntersect1 one ray at a time).
void BM_PrimaryRays(benchmark::State& state) {
  PrimaryStage& st = stage();
  const int threads = static_cast<int>(state.range(0));
  const int width = static_cast<int>(state.range(1));
  st.tracer->setPacketWidth(width);
  state.SetLabel("width " + std::to_string(st.tracer->packetWidth()));
  tbb::task_arena arena(threads);
  const int tiles = static_cast<int>(st.tileStart.size()) - 1;
  std::vector<Hit> hits(st.rays.size());
  for (auto _ : state) {
    arena.execute([&] {
      tbb::parallel_for(0, tiles, [&](int t) {
        const int a = st.tileStart[t], n = st.tileStart[t + 1] - a;
        if (width == 1) {
          for (int i = a; i < a + n; ++i) {
            Hit h;
            hits[i] = st.tracer->intersect(st.rays[i], h) ? h : Hit{};
          }
        } else {
          st.tracer->intersectPacket(st.rays.data() + a, n, hits.data() + a);
        }
      });
    });
    benchmark::DoNotOptimize(hits.data());
  }
  st.tracer->setPacketWidth(16);
  state.counters["Mrays/s"] = benchmark::Counter(double(st.rays.size()) * state.iterations() * 1e-6,
                                                 benchmark::Counter::kIsRate);
}

// End to end through runRender (load, tessellate, BVH, render). range(0): threads,
// range(1): packets on (1) or off (0).
void renderTeapot(benchmark::State& state, const char* aov) {
  RenderRequest req;
  req.scenePath = kScene;
  req.session.threads = static_cast<int>(state.range(0));
  req.aov = aov;
  req.overrides = {state.range(1) ? "render.packets=true" : "render.packets=false"};
  double render = 0.0, total = 0.0;
  for (auto _ : state) {
    RenderResult r = runRender(req);
    render += r.stats.time.render;
    total += r.stats.time.total;
    benchmark::DoNotOptimize(r.image.pixels.data());
  }
  state.SetLabel(state.range(1) ? "packets" : "single");
  state.counters["render_s"] = benchmark::Counter(render, benchmark::Counter::kAvgIterations);
  state.counters["total_s"] = benchmark::Counter(total, benchmark::Counter::kAvgIterations);
}

void BM_DepthView(benchmark::State& s) { renderTeapot(s, "depth"); }
void BM_DirectOnly(benchmark::State& s) { renderTeapot(s, "direct"); }

}  // namespace

BENCHMARK(BM_PrimaryRays)
    ->ArgsProduct({{1, 2}, {1, 4, 8, 16}})
    ->Unit(benchmark::kMillisecond)->UseRealTime()->MinTime(1.0);
BENCHMARK(BM_DepthView)->ArgsProduct({{1, 2}, {0, 1}})->Unit(benchmark::kMillisecond)->UseRealTime()->Iterations(3);
BENCHMARK(BM_DirectOnly)->ArgsProduct({{1, 2}, {0, 1}})->Unit(benchmark::kMillisecond)->UseRealTime()->Iterations(3);

BENCHMARK_MAIN();
