// Gather-stage throughput: photon-map build (Morton order on/off, leaf size) and
// per-query cost of kNN, classify(), classic() and density() at 1 and 2 threads.
// Photons lie on the inner faces of a box (a Cornell-box-like surface set); queries are
// the first hits of a pinhole camera's rays, in scan-line order or shuffled.
// The 1M cases run by default; the 5M cases are registered only when an argument
// mentions 5M, e.g.  bench_gather --benchmark_filter=5M
#include "core/rng.h"
#include "gather/photon_map.h"
#include "bench/bench_common.h"
#include <benchmark/benchmark.h>
#include <tbb/blocked_range.h>
#include <tbb/enumerable_thread_specific.h>
#include <tbb/global_control.h>
#include <tbb/parallel_for.h>
#include <algorithm>
#include <array>
#include <atomic>
#include <cstring>
#include <map>
#include <memory>
#include <string>

namespace penumbra {
namespace {

// A point uniformly on the inside of the box [-1,1]^3, with the inward face normal.
void boxSurfacePoint(Rng& rng, Vec3& p, Vec3& n) {
  int face = static_cast<int>(rng.uniform() * 6.0f);
  int axis = face % 3;
  float side = face < 3 ? -1.0f : 1.0f;
  p = Vec3(rng.uniform(), rng.uniform(), rng.uniform()) * 2.0f - 1.0f;
  p[axis] = side;
  n = Vec3(0.0f);
  n[axis] = -side;
}

// Shadow photons: a square "occluder shadow" in the middle of the floor and the back
// wall, everything else lit, so queries see lit, shadowed and edge regions.
PhotonArray<ShadowPhoton> shadowPhotons(size_t count) {
  Rng rng(12345);
  PhotonArray<ShadowPhoton> out(count);
  for (ShadowPhoton& ph : out) {
    Vec3 n;
    boxSurfacePoint(rng, ph.position, n);
    ph.normal = encodeOctahedral(n);
    ph.light = 0;
    const Vec3& p = ph.position;
    ph.shadow = (std::abs(p.x) < 0.4f && (std::abs(p.z) < 0.4f || std::abs(p.y) < 0.4f)) ? 1 : 0;
  }
  return out;
}

PhotonArray<IndirectPhoton> indirectPhotons(size_t count) {
  Rng rng(777);
  PhotonArray<IndirectPhoton> out(count);
  for (IndirectPhoton& ph : out) {
    Vec3 n;
    boxSurfacePoint(rng, ph.position, n);
    ph.normal = encodeOctahedral(n);
    ph.direction = encodeOctahedral(-n);
    ph.power = Color(rng.uniform(), rng.uniform(), rng.uniform()) * 1e-6f;
  }
  return out;
}

struct Query {
  Vec3 p, n;
};
// A 320x240 pinhole camera at (0,0,0.95) looking down -z: each ray's exit point from
// the box is where the tracer would gather. Scan-line order, or shuffled.
std::vector<Query> cameraQueries(bool shuffled) {
  const int w = 320, h = 240;
  std::vector<Query> qs;
  const Vec3 eye(0.0f, 0.0f, 0.95f);
  for (int y = 0; y < h; ++y)
    for (int x = 0; x < w; ++x) {
      Vec3 d = glm::normalize(Vec3((x + 0.5f) / w * 2 - 1, ((y + 0.5f) / h * 2 - 1) * 0.75f, -1.0f));
      float t = kInf;
      int axis = 0;
      for (int a = 0; a < 3; ++a) {
        if (d[a] == 0.0f) continue;
        float ta = ((d[a] > 0 ? 1.0f : -1.0f) - eye[a]) / d[a];
        if (ta < t) { t = ta; axis = a; }
      }
      Query q{eye + t * d, Vec3(0.0f)};
      q.n[axis] = d[axis] > 0 ? -1.0f : 1.0f;
      qs.push_back(q);
    }
  if (shuffled) {
    Rng rng(9);
    for (size_t i = qs.size() - 1; i > 0; --i)
      std::swap(qs[i], qs[static_cast<size_t>(rng.uniform() * (i + 1))]);
  }
  return qs;
}

const std::vector<Query>& queries(bool shuffled) {
  static const std::vector<Query> coherent = cameraQueries(false), random = cameraQueries(true);
  return shuffled ? random : coherent;
}

// Maps are expensive to build and to hold at 5M: keep only the most recent one of
// each kind; benchmarks are registered so that ones sharing a map run back to back.
struct MapKey {
  size_t n;
  bool morton;
  size_t leaf;
  bool operator==(const MapKey& o) const { return n == o.n && morton == o.morton && leaf == o.leaf; }
};
const ShadowPhotonMap& shadowMap(const MapKey& key) {
  static std::unique_ptr<ShadowPhotonMap> map;
  static MapKey cached{0, false, 0};
  if (!map || !(cached == key)) {
    map.reset();
    map = std::make_unique<ShadowPhotonMap>();
    map->build(shadowPhotons(key.n), 1, {key.morton, key.leaf});
    cached = key;
  }
  return *map;
}
const IndirectPhotonMap& indirectMap(const MapKey& key) {
  static std::unique_ptr<IndirectPhotonMap> map;
  static MapKey cached{0, false, 0};
  if (!map || !(cached == key)) {
    map.reset();
    map = std::make_unique<IndirectPhotonMap>();
    map->build(indirectPhotons(key.n), {key.morton, key.leaf});
    cached = key;
  }
  return *map;
}

// Runs fn(query, scratch) over all queries with `threads` workers, blocks of 64.
template <class Fn>
void runQueries(benchmark::State& state, int threads, bool shuffled, Fn fn) {
  const std::vector<Query>& qs = queries(shuffled);
  tbb::global_control limit(tbb::global_control::max_allowed_parallelism, threads);
  tbb::enumerable_thread_specific<GatherScratch> scratch;
  const bench::CpuShare cpu;
  for (auto _ : state) {
    tbb::parallel_for(tbb::blocked_range<size_t>(0, qs.size(), 64), [&](const auto& r) {
      GatherScratch& s = scratch.local();
      for (size_t i = r.begin(); i != r.end(); ++i) fn(qs[i], s);
    });
  }
  cpu.report(state, threads);
  state.SetItemsProcessed(static_cast<int64_t>(state.iterations() * qs.size()));
  // Share of queries that started from a search hint / whose hint ball was too small.
  uint64_t hinted = 0, reruns = 0;
  for (const GatherScratch& s : scratch) {
    hinted += s.hintedQueries;
    reruns += s.hintReruns;
  }
  const double total = static_cast<double>(state.iterations() * qs.size());
  state.counters["hinted"] = static_cast<double>(hinted) / total;
  state.counters["reruns"] = static_cast<double>(reruns) / total;
  // kIsRate divides by the time, kInvert flips it: seconds per query (printed as e.g. 8.1us).
  state.counters["time_per_query"] =
      benchmark::Counter(static_cast<double>(state.iterations() * qs.size()),
                         benchmark::Counter::kIsRate | benchmark::Counter::kInvert);
}

// Args: photons, morton, leaf, threads, shuffled.
MapKey keyOf(const benchmark::State& st) {
  return {static_cast<size_t>(st.range(0)), st.range(1) != 0, static_cast<size_t>(st.range(2))};
}

void BM_BuildShadow(benchmark::State& state) {
  const PhotonArray<ShadowPhoton> src = shadowPhotons(static_cast<size_t>(state.range(0)));
  tbb::global_control limit(tbb::global_control::max_allowed_parallelism,
                            static_cast<size_t>(state.range(3)));
  size_t bytes = 0;
  for (auto _ : state) {
    state.PauseTiming();
    PhotonArray<ShadowPhoton> copy = src;
    ShadowPhotonMap map;
    state.ResumeTiming();
    map.build(std::move(copy), 1, {state.range(1) != 0, static_cast<size_t>(state.range(2))});
    bytes = map.memoryBytes();
    state.PauseTiming();
    { ShadowPhotonMap dispose = std::move(map); }  // free outside the timed region
    state.ResumeTiming();
  }
  state.SetItemsProcessed(static_cast<int64_t>(state.iterations() * src.size()));
  state.counters["bytes_per_photon"] = static_cast<double>(bytes) / src.size();
}

void BM_Knn(benchmark::State& state) {
  const ShadowPhotonMap& map = shadowMap(keyOf(state));
  runQueries(state, static_cast<int>(state.range(3)), state.range(4) != 0,
             [&](const Query& q, GatherScratch& s) {
               benchmark::DoNotOptimize(map.knn(q.p, 0, 50, 0.0f, s));
             });
}

void BM_Classify(benchmark::State& state) {
  const ShadowPhotonMap& map = shadowMap(keyOf(state));
  GateParams params;
  std::array<std::atomic<int64_t>, 3> verdicts{};
  runQueries(state, static_cast<int>(state.range(3)), state.range(4) != 0,
             [&](const Query& q, GatherScratch& s) {
               GateVerdict v = map.classify(q.p, q.n, 0, params, s);
               verdicts[static_cast<int>(v)].fetch_add(1, std::memory_order_relaxed);
             });
  double total = static_cast<double>(verdicts[0] + verdicts[1] + verdicts[2]);
  state.counters["lit"] = verdicts[0] / total;
  state.counters["shadowed"] = verdicts[1] / total;
  state.counters["mixed"] = verdicts[2] / total;
}

void BM_Classic(benchmark::State& state) {
  const IndirectPhotonMap& map = indirectMap(keyOf(state));
  runQueries(state, static_cast<int>(state.range(3)), state.range(4) != 0,
             [&](const Query& q, GatherScratch& s) {
               benchmark::DoNotOptimize(map.classic(q.p, q.n, 50, 0.0f, s).value);
             });
}

void BM_Density(benchmark::State& state) {
  const IndirectPhotonMap& map = indirectMap(keyOf(state));
  runQueries(state, static_cast<int>(state.range(3)), state.range(4) != 0,
             [&](const Query& q, GatherScratch& s) {
               benchmark::DoNotOptimize(map.density(q.p, q.n, 50, 0.0f, s).value);
             });
}

void registerAll(bool with5M) {
  const MapBuildOptions def;
  const int64_t leaf = static_cast<int64_t>(def.leafSize);
  std::vector<std::pair<int64_t, std::string>> sizes = {{1'000'000, "1M"}};
  if (with5M) sizes.push_back({5'000'000, "5M"});
  for (const auto& [n, tag] : sizes) {
    auto name = [&](const char* what) { return std::string(what) + "/" + tag; };
    int64_t iters = n > 1'000'000 ? 1 : 3;
    for (int64_t morton : {0, 1})
      for (int64_t threads : {1, 2})
        benchmark::RegisterBenchmark(name("BuildShadow").c_str(), BM_BuildShadow)
            ->ArgNames({"n", "morton", "leaf", "threads"})
            ->Args({n, morton, leaf, threads})
            ->Iterations(iters)->Unit(benchmark::kMillisecond)->UseRealTime();
    // Query cost: Morton off/on and leaf sizes (one thread, both orders), then the
    // default map at 1 and 2 threads. Grouped by map so each is built once.
    std::vector<std::pair<int64_t, int64_t>> maps = {{0, leaf}};
    for (int64_t lf : {10, 16, 24, 32, 48, 64})
      if (lf != leaf) maps.push_back({1, lf});
    maps.push_back({1, leaf});  // the default last: 2-thread and estimator runs reuse it
    for (const auto& [morton, lf] : maps) {
      bool isDefault = morton == 1 && lf == leaf;
      for (int64_t threads : {1, 2}) {
        if (threads == 2 && !isDefault) continue;
        for (int64_t shuffled : {0, 1})
          benchmark::RegisterBenchmark(name("Knn50").c_str(), BM_Knn)
              ->ArgNames({"n", "morton", "leaf", "threads", "shuffled"})
              ->Args({n, morton, lf, threads, shuffled})
              ->MinTime(0.3)->UseRealTime();
        if (lf == leaf)
          for (int64_t shuffled : {0, 1})
            if (threads == 1 || shuffled == 0)
              benchmark::RegisterBenchmark(name("Classify").c_str(), BM_Classify)
                  ->ArgNames({"n", "morton", "leaf", "threads", "shuffled"})
                  ->Args({n, morton, lf, threads, shuffled})
                  ->MinTime(0.3)->UseRealTime();
      }
    }
    for (int64_t threads : {1, 2})
      for (auto* fn : {BM_Classic, BM_Density})
        for (int64_t shuffled : {0, 1})
          if (threads == 1 || shuffled == 0)
            benchmark::RegisterBenchmark(name(fn == BM_Classic ? "Classic" : "Density").c_str(), fn)
                ->ArgNames({"n", "morton", "leaf", "threads", "shuffled"})
                ->Args({n, 1, leaf, threads, shuffled})
                ->MinTime(0.3)->UseRealTime();
  }
}

}  // namespace
}  // namespace penumbra

int main(int argc, char** argv) {
  bool with5M = false;
  for (int i = 1; i < argc; ++i) with5M |= std::strstr(argv[i], "5M") != nullptr;
  penumbra::registerAll(with5M);
  return penumbra::bench::benchmarkMain(argc, argv);
}
