// The volume photon map's figures: photons per second through fog (the volume pass in
// a closed box filled with a scene medium, one thread) and the beam gather's cost per
// camera ray at the radius rule's k, with the photons each beam finds.
#include "bench/bench_common.h"
#include "core/rng.h"
#include "emit/emit_physical.h"
#include "gather/kd_tree.h"
#include "gather/volume_estimate.h"
#include "io/shapes.h"
#include <benchmark/benchmark.h>
#include <tbb/global_control.h>
#include <memory>

namespace penumbra {
namespace {

// A 5.5-unit box of grey walls filled with fog (sigma_s 0.1, sigma_a 0.01, g 0.3) and
// a point light below its ceiling: the fog room's proportions.
struct FogRoom {
  Scene scene;
  std::unique_ptr<TraceScene> tracer;
  FogRoom() {
    Material wall;
    wall.name = "wall";
    wall.diffuse = Color(0.7f);
    scene.materials.push_back(wall);
    scene.meshes.push_back(makeBox(Vec3(-2.75f), Vec3(2.75f), 0));
    Medium fog;
    fog.name = "fog";
    fog.sigmaA = Color(0.01f);
    fog.sigmaS = Color(0.1f);
    fog.g = 0.3f;
    scene.media.push_back(fog);
    scene.sceneMedium = 0;
    Light l;
    l.type = LightType::Point;
    l.position = Vec3(0.0f, 2.5f, 0.0f);
    l.intensity = 10.0f;
    l.medium = 0;
    scene.lights.push_back(l);
    scene.render.seed = 1;
    tracer = std::make_unique<TraceScene>(scene);
  }
  EmittedPhotons emit(uint64_t n, uint32_t pass = 0) const {
    EmitOptions o;
    o.maps = PerMap<bool>{};
    o.maps[MapKind::Volume] = true;
    o.budgets[MapKind::Volume] = n;
    return emitPhysicalPhotons(scene, *tracer, pass, o);
  }
};

const FogRoom& room() {
  static const FogRoom r;
  return r;
}

void BM_VolumeEmission(benchmark::State& state) {
  tbb::global_control one(tbb::global_control::max_allowed_parallelism, 1);
  const uint64_t n = static_cast<uint64_t>(state.range(0));
  size_t stored = 0;
  for (auto _ : state) stored = room().emit(n).batches.get<MapKind::Volume>().size();
  state.counters["photons_per_s"] = benchmark::Counter(double(n), benchmark::Counter::kIsIterationInvariantRate);
  state.counters["stored_per_emitted"] = double(stored) / double(n);
}
BENCHMARK(BM_VolumeEmission)->Arg(200000)->Unit(benchmark::kMillisecond);

// Camera rays from the box's front through a 512 x 512 image of its back wall, in
// scan-line order as a render traces them (second arg 1: shuffled, every beam a cache
// miss; 2: the grid walk alone, no phase or transmittance), the whole room's depth in
// fog, gathered with k photons per beam by the radius rule.
void BM_VolumeBeamGather(benchmark::State& state) {
  const int k = static_cast<int>(state.range(0));
  VolumePhotonMap map;
  map.build(room().emit(200000).batches.get<MapKind::Volume>());
  const Medium& fog = room().scene.media[0];
  GatherScratch scratch;
  constexpr int kSide = 512;
  std::vector<VolumeQuery> queries(kSide * kSide);
  for (size_t i = 0; i < queries.size(); ++i) {
    VolumeQuery& q = queries[i];
    q.origin = Vec3(0.0f, 0.0f, 2.7f);
    const float u = (i % kSide + 0.5f) / kSide, v = (i / kSide + 0.5f) / kSide;
    const Vec3 target(5.4f * u - 2.7f, 2.7f - 5.4f * v, -2.75f);
    q.tMax = glm::length(target - q.origin);
    q.dir = (target - q.origin) / q.tMax;
    q.medium = 0;
  }
  if (state.range(1) == 1) {
    Rng rng(5);
    for (size_t i = queries.size() - 1; i > 0; --i) std::swap(queries[i], queries[rng.nextU32() % (i + 1)]);
  }
  const bool walkOnly = state.range(1) == 2;
  const float radius = map.radiusFor(k);
  size_t i = 0, found = 0, beams = 0;
  for (auto _ : state) {
    VolumeEstimate e;
    const VolumeQuery& q = queries[i++ % queries.size()];
    if (walkOnly) {
      map.beam(q.origin, q.dir, q.tMin, q.tMax, radius, [&](const VolumePhoton&, float, float) { ++e.found; });
    } else {
      e = volumeRadiance(map, q, fog, k, 0.0f, scratch);
    }
    benchmark::DoNotOptimize(e);
    found += e.found;
    ++beams;
  }
  state.counters["photons_found_per_beam"] = double(found) / double(beams);
  state.counters["photons_gathered_per_s"] = benchmark::Counter(double(found), benchmark::Counter::kIsRate);
  state.counters["radius"] = map.radiusFor(k);
  state.counters["cell"] = map.cellSize();
  state.counters["map_photons"] = double(map.size());
}
BENCHMARK(BM_VolumeBeamGather)->Args({25, 0})->Args({100, 0})->Args({400, 0})->Args({100, 1})->Args({100, 2})->Unit(benchmark::kMicrosecond);

}  // namespace
}  // namespace penumbra

int main(int argc, char** argv) { return penumbra::bench::benchmarkMain(argc, argv); }
