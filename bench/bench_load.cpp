// glTF load at scale: a 1M-triangle GLB (a wavy height field with normals, uvs and
// 32-bit indices, as exporters write them), written once with tinygltf's writer, loaded
// as a scene and its Embree BVH built. Time and memory per triangle against the
// targets of docs/PERFORMANCE.md (2 s, 100 B per triangle with the BVH).
#include "bench/bench_common.h"
#include "core/stats.h"
#include "geometry/trace_scene.h"
#include "io/scene_loader.h"
#include "tests/support/gltf_build.h"
#include <benchmark/benchmark.h>
#include <malloc.h>
#include <tbb/global_control.h>
#include <algorithm>
#include <cmath>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <string>
#include <unistd.h>

using namespace penumbra;

namespace {

namespace fs = std::filesystem;

// 1000 x 500 quads, two triangles each.
constexpr int kColumns = 1000, kRows = 500;

// The scratch folder of the model, removed when the process ends.
struct ScratchFolder {
  fs::path dir = fs::temp_directory_path() / ("penumbra_bench_load_" + std::to_string(getpid()));
  ~ScratchFolder() {
    std::error_code ec;
    fs::remove_all(dir, ec);
  }
};

// The height field over [0, 4] x [0, 2] in x and z, heights +-0.2, with its exact normals.
std::string writeModel() {
  static const ScratchFolder scratch;
  const fs::path file = scratch.dir / "grid_1m.glb";
  if (fs::exists(file)) return file.string();
  fs::create_directories(scratch.dir);
  const int nx = kColumns + 1, nz = kRows + 1;
  std::vector<float> pos, nrm, uv;
  std::vector<uint32_t> idx;
  pos.reserve(size_t(nx) * nz * 3);
  nrm.reserve(size_t(nx) * nz * 3);
  uv.reserve(size_t(nx) * nz * 2);
  const double sx = 4.0 / kColumns, sz = 2.0 / kRows, k = 12.0;
  for (int j = 0; j < nz; ++j) {
    for (int i = 0; i < nx; ++i) {
      const double x = i * sx, z = j * sz;
      const double y = 0.1 * std::sin(k * x) + 0.1 * std::cos(k * z);
      const double dx = 0.1 * k * std::cos(k * x), dz = -0.1 * k * std::sin(k * z);
      const double len = std::sqrt(dx * dx + 1.0 + dz * dz);
      pos.insert(pos.end(), {float(x), float(y), float(z)});
      nrm.insert(nrm.end(), {float(-dx / len), float(1.0 / len), float(-dz / len)});
      uv.insert(uv.end(), {float(i) / kColumns, float(j) / kRows});
    }
  }
  for (int j = 0; j < kRows; ++j) {
    for (int i = 0; i < kColumns; ++i) {
      const uint32_t a = uint32_t(j * nx + i), b = a + 1, c = a + uint32_t(nx), d = c + 1;
      idx.insert(idx.end(), {a, c, b, b, c, d});
    }
  }
  tinygltf::Model m = testing::emptyGltf();
  testing::addSceneNode(m, testing::addTriangleMesh(m, pos, nrm, uv, idx));
  if (!testing::writeGltfFile(m, file.string(), true)) return "";
  return file.string();
}

// A /proc/self/status field in bytes ("VmRSS:", "VmHWM:").
uint64_t statusBytes(const char* field) {
  std::ifstream in("/proc/self/status");
  std::string line;
  while (std::getline(in, line)) {
    if (line.rfind(field, 0) == 0) return std::stoull(line.substr(std::strlen(field))) * 1024;
  }
  return 0;
}

// Resets VmHWM to the current RSS, so each iteration's peak is its own.
void resetPeak() { std::ofstream("/proc/self/clear_refs") << "5"; }

// loadScene of the GLB (the model checked, parsed, transformed, its defaults added)
// and the TraceScene (Embree BVH, in `layout`) built from it. Memory, per triangle:
// peak RSS above the RSS before the load (freed heap trimmed first; the peak reset
// through /proc/self/clear_refs), and the RSS still held with the scene and BVH alive.
void loadGltf1M(benchmark::State& state, BvhLayout layout) {
  const std::string file = writeModel();
  if (file.empty()) {
    state.SkipWithError("cannot write the 1M-triangle GLB");
    return;
  }
  const int threads = static_cast<int>(state.range(0));
  tbb::global_control limit(tbb::global_control::max_allowed_parallelism, static_cast<size_t>(threads));
  double load = 0.0, bvh = 0.0, peak = 0.0, held = 0.0, loadPeak = 0.0, sceneHeld = 0.0, sceneArrays = 0.0;
  double bvhPeak = 0.0;
  uint64_t triangles = 0;
  const penumbra::bench::CpuShare cpu;
  for (auto _ : state) {
    malloc_trim(0);
    resetPeak();
    const uint64_t before = statusBytes("VmRSS:");
    Stopwatch clock;
    {
      const Scene scene = loadScene(file);
      load += clock.seconds();
      const double loadHwm = double(statusBytes("VmHWM:") - before);
      const uint64_t loaded = statusBytes("VmRSS:");
      loadPeak += loadHwm;
      sceneHeld += double(loaded - before);
      for (const TriangleMesh& m : scene.meshes) {
        sceneArrays += double(m.positions.size() * sizeof(Vec3) + m.normals.size() * sizeof(Vec3) +
                              m.uvs.size() * sizeof(Vec2) + m.triangles.size() * sizeof(m.triangles[0]));
      }
      resetPeak();  // the build's own peak, above the loaded scene
      Stopwatch build;
      const TraceScene tracer(scene, true, layout);
      bvh += build.seconds();
      triangles = 0;
      for (const TriangleMesh& m : scene.meshes) triangles += m.triangles.size();
      const double buildHwm = double(statusBytes("VmHWM:") - loaded);
      bvhPeak += buildHwm;
      held += double(statusBytes("VmRSS:") - before);
      peak += std::max(loadHwm, double(loaded - before) + buildHwm);
      benchmark::DoNotOptimize(&tracer);
    }
    state.SetIterationTime(clock.seconds());
  }
  cpu.report(state, threads);
  const double n = double(state.iterations()), tris = double(triangles);
  state.counters["triangles"] = tris;
  state.counters["load_s"] = load / n;
  state.counters["bvh_s"] = bvh / n;
  state.counters["peak_B_per_tri"] = peak / n / tris;
  state.counters["held_B_per_tri"] = held / n / tris;
  // Where it goes: the load's own peak, the RSS the loaded scene holds, its mesh
  // arrays counted exactly, and the TraceScene's build peak above the loaded scene
  // (the rest of held is the TraceScene: BVH and per-triangle frames; Embree reads
  // the scene's vertices and indices in place).
  state.counters["load_peak_B_per_tri"] = loadPeak / n / tris;
  state.counters["scene_held_B_per_tri"] = sceneHeld / n / tris;
  state.counters["scene_arrays_B_per_tri"] = sceneArrays / n / tris;
  state.counters["bvh_peak_B_per_tri"] = bvhPeak / n / tris;
}

// The layout TraceScene picks (compact: the model has kCompactBvhTriangles), and
// Embree's default layout beside it for what compact saves.
void BM_LoadGltf1M(benchmark::State& state) { loadGltf1M(state, BvhLayout::Auto); }
void BM_LoadGltf1MFastLayout(benchmark::State& state) { loadGltf1M(state, BvhLayout::Fast); }

BENCHMARK(BM_LoadGltf1M)->ArgName("threads")->Arg(1)->Arg(2)->Iterations(1)->UseManualTime()->Unit(benchmark::kSecond);
BENCHMARK(BM_LoadGltf1MFastLayout)->ArgName("threads")->Arg(1)->Iterations(1)->UseManualTime()->Unit(benchmark::kSecond);

}  // namespace

int main(int argc, char** argv) { return penumbra::bench::benchmarkMain(argc, argv); }
