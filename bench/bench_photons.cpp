// The photon pass on the Cornell-style box (5M shadow + 5M indirect photons): emission
// throughput, the batch merge that ends it, and the two KD-tree builds, at 1 and 2
// threads (docs/PERFORMANCE.md: the photon pass and the scaling targets).
#include "emit/batch_buffers.h"
#include "emit/emit.h"
#include "gather/photon_map.h"
#include "io/scene_loader.h"
#include "bench/bench_common.h"
#include <benchmark/benchmark.h>
#include <tbb/global_control.h>
#include <tbb/parallel_invoke.h>

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
    PhotonMaps maps = emitPhotons(scene, tracer);
    emitted += maps.emittedShadow + maps.emittedIndirect;
    stored += maps.shadow.size() + maps.indirect.size();
  }
  cpu.report(state, static_cast<int>(state.range(0)));
  state.SetItemsProcessed(static_cast<int64_t>(emitted));
  state.counters["stored_per_iter"] = benchmark::Counter(double(stored), benchmark::Counter::kAvgIterations);
}

void BM_BuildMapsCornell(benchmark::State& state) {
  tbb::global_control limit(tbb::global_control::max_allowed_parallelism, state.range(0));
  Scene scene = cornell();
  TraceScene tracer(scene);
  PhotonMaps maps = emitPhotons(scene, tracer);
  for (auto _ : state) {
    state.PauseTiming();
    PhotonArray<ShadowPhoton> shadow = maps.shadow;
    PhotonArray<IndirectPhoton> indirect = maps.indirect;
    ShadowPhotonMap shadowMap;
    IndirectPhotonMap indirectMap;
    state.ResumeTiming();
    tbb::parallel_invoke([&] { shadowMap.build(std::move(shadow), scene.lights.size()); },
                         [&] { indirectMap.build(std::move(indirect)); });
    benchmark::DoNotOptimize(shadowMap.size() + indirectMap.size());
    state.counters["bytes"] = double(shadowMap.memoryBytes() + indirectMap.memoryBytes());
  }
  state.SetItemsProcessed(static_cast<int64_t>(state.iterations() * (maps.shadow.size() + maps.indirect.size())));
}

// The merge that ends each emission pass, alone: fig14's stored counts (4.76M shadow +
// 6.99M indirect photons) in batches of what 4096 emitted photons store. The output
// array is value-initialised on the calling thread before the parallel copy, so this
// is the serial share of the emission's time (docs/PERFORMANCE.md, scaling targets).
template <class Photon>
BatchBuffers<Photon> filledBatches(size_t total, size_t perBatch) {
  BatchBuffers<Photon> buffers((total + perBatch - 1) / perBatch);
  for (size_t b = 0, left = total; left > 0; ++b) {
    const size_t n = std::min(perBatch, left);
    buffers.batch(b).assign(n, Photon{});
    left -= n;
  }
  return buffers;
}

void BM_MergeCornell(benchmark::State& state) {
  tbb::global_control limit(tbb::global_control::max_allowed_parallelism, state.range(0));
  for (auto _ : state) {
    state.PauseTiming();
    auto shadow = filledBatches<ShadowPhoton>(4'760'000, 4'760'000 / 1221);
    auto indirect = filledBatches<IndirectPhoton>(6'990'000, 6'990'000 / 1221);
    state.ResumeTiming();
    PhotonArray<ShadowPhoton> s = shadow.merge();
    PhotonArray<IndirectPhoton> i = indirect.merge();
    benchmark::DoNotOptimize(s.data());
    benchmark::DoNotOptimize(i.data());
    state.PauseTiming();  // freeing the 263 MB is not the merge's
    { auto drop = std::move(s); auto drop2 = std::move(i); }
    state.ResumeTiming();
  }
}

}  // namespace

// `make bench` runs 3 repetitions, interleaved; run alone, raise --benchmark_repetitions.
BENCHMARK(BM_EmitCornell)->Arg(1)->Arg(2)->Unit(benchmark::kMillisecond)->UseRealTime()->Iterations(1);
BENCHMARK(BM_MergeCornell)->Arg(1)->Arg(2)->Unit(benchmark::kMillisecond)->UseRealTime()->Iterations(3);
BENCHMARK(BM_BuildMapsCornell)->Arg(1)->Arg(2)->Unit(benchmark::kMillisecond)->UseRealTime()->Iterations(1);

PENUMBRA_BENCHMARK_MAIN()
