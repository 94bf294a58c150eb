// Driver of the distance-to-the-limit profile (scripts/profile_render.py): REPS renders of
// one scene with their CLOCK_MONOTONIC windows and counters for perf, then in the same run
// the raw Embree and nanoflann rates on that scene's rays and first-hit points.
#include "bench/bench_common.h"
#include "tests/support/emit_fixtures.h"
#include "plan/pipeline.h"
#include "emit/emit.h"
#include "emit/emit_physical.h"
#include "gather/photon_map.h"
#include "io/scene_loader.h"
#include <nanoflann.hpp>
#include <tbb/enumerable_thread_specific.h>
#include <atomic>
#include <cstdio>
#include <ctime>
#include <fstream>
#include <mutex>

using namespace penumbra;
using namespace penumbra::bench;

namespace {

double monotonicNow() {
  timespec ts;
  clock_gettime(CLOCK_MONOTONIC, &ts);
  return double(ts.tv_sec) + 1e-9 * double(ts.tv_nsec);
}

// Nanoseconds per k-nearest query (through the KD facade the renderer calls: nanoflann's
// searchLevel over the Morton parts) at `points`, `threads` workers, fastest of 3 passes.
template <class Query>
double nsPerQuery(const std::vector<Vec3>& points, int threads, Query query, int passes = 3) {
  tbb::global_control limit(tbb::global_control::max_allowed_parallelism, threads);
  tbb::enumerable_thread_specific<GatherScratch> scratch;
  double best = 1e30;
  for (int pass = 0; pass < passes; ++pass) {
    std::atomic<size_t> found{0};
    const double t0 = monotonicNow();
    tbb::parallel_for(tbb::blocked_range<size_t>(0, points.size(), 64), [&](const auto& r) {
      GatherScratch& s = scratch.local();
      size_t n = 0;
      for (size_t i = r.begin(); i != r.end(); ++i) n += query(points[i], s);
      found += n;
    });
    best = std::min(best, (monotonicNow() - t0) * 1e9 / double(points.size()));
  }
  return best;
}

// The library's own ceiling: one plain nanoflann tree (leaf size 24, as the maps) over the
// same photons, KNNResultSet queries of the same k at every 4th of the same points (in
// order), one pass: no parts, no hints. Much slower than the facade, so kept short.
struct Cloud {
  const PhotonArray<IndirectPhoton>* photons;
  size_t kdtree_get_point_count() const { return photons->size(); }
  float kdtree_get_pt(size_t i, size_t dim) const { return (&(*photons)[i].position.x)[dim]; }
  template <class BBox>
  bool kdtree_get_bbox(BBox&) const { return false; }
};
double nanoflannNs(const PhotonArray<IndirectPhoton>& photons, size_t k, const std::vector<Vec3>& points,
                   int threads) {
  using Tree = nanoflann::KDTreeSingleIndexAdaptor<nanoflann::L2_Simple_Adaptor<float, Cloud>, Cloud, 3, uint32_t>;
  const Cloud cloud{&photons};
  Tree tree(3, cloud, nanoflann::KDTreeSingleIndexAdaptorParams(24));
  tree.buildIndex();
  struct Buffers {
    std::vector<uint32_t> idx;
    std::vector<float> d2;
  };
  tbb::enumerable_thread_specific<Buffers> buffers;
  std::vector<Vec3> every4th;
  for (size_t i = 0; i < points.size(); i += 4) every4th.push_back(points[i]);
  return nsPerQuery(every4th, threads, [&](const Vec3& p, GatherScratch&) {
    Buffers& b = buffers.local();
    b.idx.resize(k);
    b.d2.resize(k);
    nanoflann::KNNResultSet<float, uint32_t> result(k);
    result.init(b.idx.data(), b.d2.data());
    tree.findNeighbors(result, &p.x, nanoflann::SearchParams());
    return size_t(result.size());
  }, 1);
}

// The scene's own photon maps (pass 0 / the classic pass), queried with its own k.
// Skipped (classic) when the render made no exact queries: photons.gate auto left the
// shadow map out and there is no indirect map.
void rawGatherRates(const Scene& scene, const TraceScene& tracer, const RaySets& rays, int threads,
                    bool queried, std::FILE* out) {
  const PhotonSettings& ps = scene.photons;
  if (scene.render.model == ShadingModel::Physical) {
    EmittedPhotons ph = emitPhysicalPhotons(scene, tracer, 0, sceneEmit(scene));
    IndirectPhotonMap global, caustic;
    global.build(std::move(ph.batches.get<MapKind::Global>()));
    caustic.build(std::move(ph.batches.get<MapKind::Caustic>()));
    const double g = nsPerQuery(rays.points, threads, [&](const Vec3& p, GatherScratch& s) {
      return global.knn(p, size_t(ps.kGlobal), 0.0f, s);
    });
    const double c = nsPerQuery(rays.points, threads, [&](const Vec3& p, GatherScratch& s) {
      return caustic.knn(p, size_t(ps.kCaustic), 0.0f, s);
    });
    const double ng = nanoflannNs(global.photons(), size_t(ps.kGlobal), rays.points, threads);
    const double nc = nanoflannNs(caustic.photons(), size_t(ps.kCaustic), rays.points, threads);
    std::fprintf(out, "\"knn_global_ns\": %.1f, \"knn_caustic_ns\": %.1f, \"nanoflann_global_ns\": %.1f, "
                 "\"nanoflann_caustic_ns\": %.1f, \"k_global\": %d, \"k_caustic\": %d, "
                 "\"global_photons\": %zu, \"caustic_photons\": %zu",
                 g, c, ng, nc, ps.kGlobal, ps.kCaustic, global.size(), caustic.size());
    return;
  }
  if (!queried) {
    std::fprintf(out, "\"exact_queries\": 0");
    return;
  }
  EmittedPhotons maps = emitPhotons(scene, tracer, sceneEmit(scene));
  ShadowPhotonMap shadow;
  IndirectPhotonMap indirect;
  shadow.build(std::move(maps.batches.get<MapKind::Shadow>()), scene.lights.size());
  indirect.build(std::move(maps.batches.get<MapKind::Indirect>()));
  const double i = nsPerQuery(rays.points, threads, [&](const Vec3& p, GatherScratch& s) {
    return indirect.size() ? indirect.knn(p, size_t(ps.kIndirect), ps.maxRadius, s) : 0;
  });
  const double g = nsPerQuery(rays.points, threads, [&](const Vec3& p, GatherScratch& s) {
    return shadow.size() ? shadow.knn(p, 0, size_t(ps.kShadow), 0.0f, s) : 0;
  });
  const double ni = indirect.size() ? nanoflannNs(indirect.photons(), size_t(ps.kIndirect), rays.points, threads) : 0;
  std::fprintf(out, "\"knn_indirect_ns\": %.1f, \"knn_shadow_ns\": %.1f, \"nanoflann_indirect_ns\": %.1f, "
               "\"k_indirect\": %d, \"k_shadow\": %d, \"indirect_photons\": %zu, \"shadow_photons\": %zu",
               i, g, ni, ps.kIndirect, ps.kShadow, indirect.size(), shadow.size());
}

}  // namespace

// profile_render SCENE.json THREADS REPS OUT.json [key=value ...]
int main(int argc, char** argv) {
  if (argc < 5) {
    std::fprintf(stderr, "usage: %s SCENE.json THREADS REPS OUT.json [key=value ...]\n", argv[0]);
    return 2;
  }
  RenderRequest req;
  req.scenePath = argv[1];
  req.session.threads = std::atoi(argv[2]);
  const int reps = std::atoi(argv[3]);
  for (int i = 5; i < argc; ++i) req.overrides.push_back(argv[i]);
  std::FILE* out = std::fopen(argv[4], "w");
  if (!out) return 2;
  std::fprintf(out, "{\"scene\": \"%s\", \"threads\": %d, \"renders\": [\n", argv[1], req.session.threads);
  bool queried = false;
  // The render phase's start, announced by the session on its own thread.
  struct RenderStart final : ProgressPhases {
    double t = 0.0;
    ProgressCounter* begin(const std::string& phase, uint64_t) override {
      if (t == 0.0 && phase.rfind("render", 0) == 0) t = monotonicNow();
      return nullptr;
    }
    void end() override {}
  };
  for (int rep = 0; rep < reps; ++rep) {
    RenderStart renderStart;
    req.session.progress = &renderStart;
    const double t0 = monotonicNow();
    const RenderResult r = runRender(req);
    const double t1 = monotonicNow();
    const RenderStats& s = r.stats;
    queried = s.rays.gatherQueries + s.rays.gateQueries > 0;
    std::fprintf(out,
                 "%s{\"t0\": %.6f, \"t1\": %.6f, \"render_t0\": %.6f, \"total_s\": %.4f, \"render_s\": %.4f, "
                 "\"emit_s\": %.4f, \"maps_s\": %.4f, \"precompute_s\": %.4f, \"camera_rays\": %llu, "
                 "\"shadow_rays\": %llu, \"secondary_rays\": %llu, \"gathers\": %llu, \"gate_queries\": %llu, "
                 "\"cache_lookups\": %llu, \"cache_fallbacks\": %llu}\n",
                 rep ? "," : "", t0, t1, renderStart.t, s.time.total, s.time.render, s.time.emit,
                 s.time.buildMaps, s.time.precompute, (unsigned long long)s.rays.camera,
                 (unsigned long long)s.rays.shadow,
                 (unsigned long long)(s.rays.reflection + s.rays.refraction),
                 (unsigned long long)s.rays.gatherQueries, (unsigned long long)s.rays.gateQueries,
                 (unsigned long long)s.rays.cacheLookups, (unsigned long long)s.rays.cacheFallbacks);
  }
  // The raw rates, after the renders (so the profile windows above hold only renders).
  const double rawT0 = monotonicNow();
  const Scene scene = loadScene(req.scenePath, req.overrides);
  const TraceScene tracer(scene);
  const RaySets rays = makeRaySets(scene, tracer);
  std::fprintf(out, "], \"raw\": {\"t0\": %.6f, \"camera_ns\": %.2f, \"shadow_ns\": %.2f, \"incoherent_ns\": %.2f, ",
               rawT0, nsPerRay(tracer, rays.camera, false, req.session.threads),
               nsPerRay(tracer, rays.shadow, true, req.session.threads),
               nsPerRay(tracer, rays.incoherent, false, req.session.threads));
  rawGatherRates(scene, tracer, rays, req.session.threads, queried, out);
  std::fprintf(out, ", \"points\": %zu}}\n", rays.points.size());
  std::fclose(out);
  return 0;
}
