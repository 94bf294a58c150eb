// The photon pass on the Cornell-style box (5M shadow + 5M indirect photons): emission
// throughput, the two map builds (sorted straight out of the emission's batches), and
// the whole pass, at 1 and 2 threads (docs/PERFORMANCE.md: the photon pass and the
// scaling targets).
#include "emit/emit.h"
#include "tests/support/emit_fixtures.h"
#include "gather/photon_map.h"
#include "io/scene_loader.h"
#include "bench/bench_common.h"
#include <benchmark/benchmark.h>
#include <tbb/global_control.h>
#include <memory>

using namespace penumbra;

namespace {

Scene cornell() {
  return loadScene(std::string(PENUMBRA_SOURCE_DIR) + "/scenes/fig14_cornell.json",
                   {"photons.shadow=5000000", "photons.indirect=5000000"});
}

void BM_EmitCornell(benchmark::State& state) {
  tbb::global_control limit(tbb::global_control::max_allowed_parallelism, state.range(0));
  Scene scene = cornell();
  TraceScene tracer(scene);
  uint64_t emitted = 0, stored = 0;
  const penumbra::bench::CpuShare cpu;
  for (auto _ : state) {
    EmittedPhotons maps = emitPhotons(scene, tracer, sceneEmit(scene));
    emitted += maps.emitted[MapKind::Shadow] + maps.emitted[MapKind::Indirect];
    stored += maps.batches.get<MapKind::Shadow>().size() + maps.batches.get<MapKind::Indirect>().size();
  }
  cpu.report(state, static_cast<int>(state.range(0)));
  state.SetItemsProcessed(static_cast<int64_t>(emitted));
  state.counters["stored_per_iter"] = benchmark::Counter(double(stored), benchmark::Counter::kAvgIterations);
}

// Both maps, built one after the other as buildStage (cli/photon_stage.cpp) does
// for maps this large.
struct Maps {
  ShadowPhotonMap shadow;
  IndirectPhotonMap indirect;
  Maps(EmittedPhotons& emitted, size_t numLights) {
    shadow.build(std::move(emitted.batches.get<MapKind::Shadow>()), numLights);
    indirect.build(std::move(emitted.batches.get<MapKind::Indirect>()));
  }
};

// Both maps built from one emission's batches (the emission itself is not timed).
void BM_BuildMapsCornell(benchmark::State& state) {
  tbb::global_control limit(tbb::global_control::max_allowed_parallelism, state.range(0));
  Scene scene = cornell();
  TraceScene tracer(scene);
  size_t stored = 0;
  for (auto _ : state) {
    state.PauseTiming();
    EmittedPhotons emitted = emitPhotons(scene, tracer, sceneEmit(scene));
    stored = emitted.batches.get<MapKind::Shadow>().size() + emitted.batches.get<MapKind::Indirect>().size();
    state.ResumeTiming();
    auto maps = std::make_unique<Maps>(emitted, scene.lights.size());
    state.counters["bytes"] = double(maps->shadow.memoryBytes() + maps->indirect.memoryBytes());
    state.PauseTiming();  // freeing the maps is not the build's
    maps.reset();
    state.ResumeTiming();
  }
  state.SetItemsProcessed(static_cast<int64_t>(state.iterations() * stored));
}

// The whole photon pass, the unit issue 8 sets its time target for (on 2 threads):
// both emissions, then both maps.
void BM_PhotonPassCornell(benchmark::State& state) {
  tbb::global_control limit(tbb::global_control::max_allowed_parallelism, state.range(0));
  Scene scene = cornell();
  TraceScene tracer(scene);
  const penumbra::bench::CpuShare cpu;
  for (auto _ : state) {
    EmittedPhotons emitted = emitPhotons(scene, tracer, sceneEmit(scene));
    auto maps = std::make_unique<Maps>(emitted, scene.lights.size());
    benchmark::DoNotOptimize(maps->shadow.size() + maps->indirect.size());
    state.PauseTiming();  // freeing the maps is not the pass's
    maps.reset();
    state.ResumeTiming();
  }
  cpu.report(state, static_cast<int>(state.range(0)));
}

}  // namespace

// `make bench` runs 3 repetitions, interleaved; run alone, raise --benchmark_repetitions.
BENCHMARK(BM_EmitCornell)->Arg(1)->Arg(2)->Unit(benchmark::kMillisecond)->UseRealTime()->Iterations(1);
BENCHMARK(BM_BuildMapsCornell)->Arg(1)->Arg(2)->Unit(benchmark::kMillisecond)->UseRealTime()->Iterations(1);
BENCHMARK(BM_PhotonPassCornell)->Arg(1)->Arg(2)->Unit(benchmark::kMillisecond)->UseRealTime()->Iterations(1);

PENUMBRA_BENCHMARK_MAIN()
