// Emission and map builds for one render or a group of renders sharing photons.
#include "plan/photon_stage.h"
#include "core/stats.h"
#include "plan/transport_model.h"
#include <tbb/parallel_for.h>
#include <exception>

namespace penumbra {
namespace {
// Up to this many photons in all, the maps are built side by side (each build is
// deterministic on its own, so the order changes nothing but the schedule).
constexpr size_t kSideBySidePhotons = size_t(1) << 21;

template <class Photon>
PhotonBatches<Photon> photonsFor(PhotonBatches<Photon>& all, const PrefixCuts& cuts, uint64_t full,
                                 uint64_t wanted, bool consume, bool& ok) {
  if (wanted == full) return consume ? std::move(all) : all;
  const PrefixCut* cut = cuts.find(wanted);
  if (!cut) {
    ok = false;
    return {};
  }
  return takePrefix(all, *cut);
}

// The photons the emitters will trace, so the bar's total is known up front: each
// map's budget, unless the emitter skips that map (no gate, no specular target).
uint64_t photonsAskedFor(const Scene& scene, const EmitOptions& o, const MapCounts& b) {
  if (scene.lights.empty()) return 0;
  uint64_t n = 0;
  for (MapKind k : kAllMaps) {
    if (o.maps[k] && (k != MapKind::Caustic || (b[k] > 0 && !specularTargets(scene).empty()))) n += b[k];
  }
  return n;
}

}  // namespace

PhotonNeeds photonNeeds(const RenderPlan& plan) {
  PhotonNeeds needs;
  for (MapKind k : kAllMaps) {
    needs.maps[k] = plan[photonPass(k)].on;
    needs.reach[k] = plan[photonPass(k)].reach;
  }
  return needs;
}

MapCounts planBudgets(const RenderPlan& plan) {
  MapCounts b;
  for (MapKind k : kAllMaps) b[k] = plan[photonPass(k)].on ? plan[photonPass(k)].budget : 0;
  return b;
}

Emission emitPhotonsFor(const Scene& scene, const TraceScene& tracer, const PhotonNeeds& needs,
                        const MapCounts& budgets, uint32_t pass, const std::vector<uint64_t>& smaller,
                        ProgressCounter* progress) {
  const TransportModel& model = transportOf(scene);
  Emission e;
  e.numLights = scene.lights.size();
  if (!needs.any()) return e;
  Stopwatch clock;
  EmitOptions options;
  options.budgets = budgets;
  options.prefixBudgets = smaller;
  options.reach = needs.reach;
  options.maps = model.emittedMaps(needs.maps, pass);
  options.progress = progress;
  progressExpect(progress, photonsAskedFor(scene, options, budgets));
  model.emit(scene, tracer, options, pass, e);
  e.budgets = e.photons.emitted;
  e.seconds = clock.seconds();
  return e;
}

bool buildStage(Emission& e, const MapCounts& wanted, bool consume, PhotonStage& stage,
                ProgressCounter* progress) {
  bool ok = true;
  // A map the emission left empty (not needed, or no light) stays empty at any budget.
  auto budget = [](uint64_t emitted, uint64_t want) { return emitted == 0 ? 0 : want; };
  MapCounts b;
  for (MapKind k : kAllMaps) b[k] = budget(e.budgets[k], wanted[k]);
  MapSlots<PhotonBatches> taken;
  taken.forEach([&](auto k, auto& photons) {
    photons = photonsFor(e.photons.batches.get<decltype(k)::value>(), e.photons.cuts[k], e.budgets[k], b[k], consume, ok);
  });
  if (!ok) return false;

  stage.budgets = b;
  stage.fromPrefix = !(b == e.budgets);
  stage.emitted = b;
  // A prefix's own emission was not timed: charge it its share of the photons
  // (emission time is linear in the photons traced; docs/sweep.md).
  const double full = double(e.budgets.total()), part = double(b.total());
  stage.emitSeconds = full > 0.0 ? e.seconds * part / full : e.seconds;
  stage.notes = e.notes;
  // Converts stored flux back into photon colour: emitted / (4 pi x summed intensity).
  stage.classicScale = e.photons.classicScale;
  const MapKind indirect = MapKind::Indirect;
  if (stage.fromPrefix && e.budgets[indirect] > 0) {
    stage.classicScale = e.photons.classicScale * float(double(b[indirect]) / double(e.budgets[indirect]));
  }
  Stopwatch clock;
  MapBuildOptions build;
  build.progress = progress;
  build.shadowTrees = false;  // a frame that votes exactly builds them (renderFrame)
  size_t photons = 0;
  taken.forEach([&photons](MapKind, const auto& batches) { photons += batches.size(); });
  progressExpect(progress, 2 * photons);
  auto buildMap = [&](MapKind kind) {
    stage.maps.with(kind, [&](auto k, auto& map) {
      auto& batches = taken.get<decltype(k)::value>();
      if constexpr (decltype(k)::value == MapKind::Shadow) map.build(std::move(batches), e.numLights, build);
      else map.build(std::move(batches), build);
    });
  };
  if (photons <= kSideBySidePhotons) {
    // Small maps: a tree under one part builds on one thread, so only building the
    // maps side by side keeps both cores busy (cornell_physical's two maps, say).
    // Each build keeps its own exception (out of memory): one escaping would cancel
    // the others' inner loops half-way; the first is rethrown once all have ended.
    std::exception_ptr failed[kMapKinds];
    tbb::parallel_for(
        tbb::blocked_range<size_t>(0, kMapKinds, 1),
        [&](const tbb::blocked_range<size_t>& kinds) {
          for (size_t i = kinds.begin(); i != kinds.end(); ++i) {
            try {
              buildMap(kAllMaps[i]);
            } catch (...) {
              failed[i] = std::current_exception();
            }
          }
        },
        tbb::simple_partitioner());
    for (const std::exception_ptr& error : failed)
      if (error) std::rethrow_exception(error);
  } else {
    // Large maps one after another, each parallel inside (its sort by chunks, its
    // tree by parts): a map's sorted array then reuses the memory the previous map's
    // batches just freed, where building side by side asked for fresh pages for all.
    for (MapKind k : kAllMaps) buildMap(k);
  }
  stage.buildSeconds = clock.seconds();
  return true;
}

}  // namespace penumbra
