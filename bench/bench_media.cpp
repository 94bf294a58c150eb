// The fog room's row of docs/PERFORMANCE.md, on 2 threads: wall, CPU seconds and share
// of the shipped render; its own error estimate against its error from the project's
// 16x longer render (same seed: the first passes are the shipped ones); photons per
// second through fog beside the surface maps'; and each map's gather cost per camera
// ray, from renders that leave one kind of map out.
#include "bench/bench_common.h"
#include "plan/pipeline.h"
#include <cmath>

using namespace penumbra;

namespace {

constexpr int kThreads = 2;
constexpr int kPasses = 8;  // scenes/cornell_fog.json's photons.passes

RenderResult fog(std::vector<std::string> overrides, std::vector<Pass> disable = {}) {
  RenderRequest req;
  req.scenePath = bench::scenePath("cornell_fog.json");
  req.session.threads = kThreads;
  req.session.plan.disable = std::move(disable);
  req.overrides = std::move(overrides);
  return runRender(req);
}

double rmse(const Image& a, const Image& b) {
  double squares = 0.0;
  for (size_t i = 0; i < a.pixels.size(); ++i) {
    for (int c = 0; c < 3; ++c) squares += std::pow(double(a.pixels[i][c]) - b.pixels[i][c], 2);
  }
  return std::sqrt(squares / (3.0 * a.pixels.size()));
}

// CPU nanoseconds per camera ray the render phase spent beyond `without`'s.
double extraNsPerRay(const RenderResult& with, const RenderResult& without) {
  const double extra = (with.stats.time.render - without.stats.time.render) * kThreads;
  return extra / std::max<double>(1.0, double(with.stats.rays.camera)) * 1e9;
}

void BM_FogRoom(benchmark::State& state) {
  for (auto _ : state) {
    const RenderResult shipped = fog({});
    state.counters["wall_s"] = shipped.stats.time.total;
    state.counters["cpu_s"] = shipped.stats.cpu.cpuSeconds;
    state.counters["cpu_share"] = shipped.stats.cpu.share;
    state.counters["estimate_rmse"] = shipped.stats.error.noiseRmse;
    const RenderResult reference = fog({"photons.passes=" + std::to_string(16 * kPasses)});
    const double measured = rmse(shipped.image, reference.image);
    state.counters["measured_rmse"] = measured;
    state.counters["estimate_over_measured"] = shipped.stats.error.noiseRmse / measured;

    // Photons per second of emission: the volume map alone, then the surface maps alone.
    const RenderResult volumeOnly = fog({}, {Pass::GlobalPhotons, Pass::CausticPhotons});
    const RenderResult surfaceOnly = fog({}, {Pass::VolumePhotons});
    const RenderResult noMaps = fog({}, {Pass::GlobalPhotons, Pass::CausticPhotons, Pass::VolumePhotons});
    const MapCounts& v = volumeOnly.stats.emitted;
    const MapCounts& s = surfaceOnly.stats.emitted;
    state.counters["volume_photons_per_s"] = double(v[MapKind::Volume]) / volumeOnly.stats.time.emit;
    state.counters["surface_photons_per_s"] = double(s[MapKind::Global] + s[MapKind::Caustic]) / surfaceOnly.stats.time.emit;
    // Each map's gathers per camera ray, in CPU ns: the render phase with it less without it.
    state.counters["volume_gather_ns_per_ray"] = extraNsPerRay(shipped, surfaceOnly);
    state.counters["surface_gather_ns_per_ray"] = extraNsPerRay(surfaceOnly, noMaps);
    state.counters["volume_mean_neighbours"] =
        double(shipped.stats.rays.volumeNeighbours) / std::max<uint64_t>(1, shipped.stats.rays.volumeGathers);
    state.counters["surface_mean_neighbours"] =
        double(shipped.stats.rays.gatherNeighbours) / std::max<uint64_t>(1, shipped.stats.rays.gatherQueries);
  }
}
BENCHMARK(BM_FogRoom)->Iterations(1)->Unit(benchmark::kSecond)->UseRealTime();

}  // namespace

PENUMBRA_BENCHMARK_MAIN()
