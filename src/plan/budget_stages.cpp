// The session's photon stages for jobs that share one emission and differ in their
// photon budgets (RenderSession::photonsByBudget): the largest emitted once, each
// budget's maps cut from it, and each stage's cost as a lone render would pay it.
#include "plan/render_session.h"
#include "plan/transport_model.h"
#include <algorithm>
#include <filesystem>
#include <stdexcept>

namespace penumbra {

void RenderSession::photonsByBudget(const std::vector<const PlannedJob*>& jobs,
                                    const std::function<void(BudgetStage&)>& visit) {
  const PlannedJob& lead = *jobs.front();
  PhotonNeeds needs;
  MapCounts top;
  std::vector<uint64_t> smaller;
  std::vector<MapCounts> budgets;
  for (const PlannedJob* j : jobs) {
    if (!j->prepared) throw std::logic_error("photons of a job not prepared");
    if (!(j->keys == lead.keys)) throw std::logic_error("one emission for jobs that differ");
    const MapCounts b = planBudgets(j->plan);
    needs |= photonNeeds(j->plan);
    top.maxWith(b);
    for (uint64_t n : b.values) smaller.push_back(n);
    if (std::find(budgets.begin(), budgets.end(), b) == budgets.end()) budgets.push_back(b);
  }
  const TraceScene& tracer = *geometry(lead).tracer;
  const CpuSpan emitting;
  // Map files hold what a render of the largest budget emits: a group of one budget
  // loads or writes its file; a larger group emits (its prefixes need the emission)
  // and writes the largest budget's file if there is none. A prefix is never written.
  const PhotonStageKey key{lead.keys.geometry, lead.keys.photons, top, needs.maps};
  MapFileOutcome file;
  Emission emission = [&] {
    const PhaseGuard phase(options_.progress);
    auto emit = [&] {
      return emitPhotonsFor(lead.scene, tracer, needs, top, 0, smaller, beginPhase(options_.progress, "photons"));
    };
    if (budgets.size() == 1) return stageEmission(lead, key, needs, emit, file);
    Emission e = emit();
    if (usesMapFile(lead, needs) && std::find(budgets.begin(), budgets.end(), top) != budgets.end()) {
      const std::string text = mapFileKey(key, needs, options_.load.defaults);
      const std::string path = mapFilePath(options_.mapDir, text);
      if (!std::filesystem::exists(path)) {
        writeMapFile(path, text, e);
        ++mapWrites_;
      }
    }
    return e;
  }();
  if (!file.loaded) ++emissions_;
  std::stable_sort(budgets.begin(), budgets.end(),
                   [](const MapCounts& a, const MapCounts& b) { return a.total() > b.total(); });
  // The shared emission is charged to the first budget, in wall and CPU time alike.
  double shared = emitting.wallSeconds(), sharedCpu = emitting.cpuSeconds();
  const double emittedCpu = sharedCpu;
  for (const MapCounts& b : budgets) {
    BudgetStage s;
    const CpuSpan build;
    bool alone = false;
    {
      const PhaseGuard phase(options_.progress);
      if (!buildStage(emission, b, false, s.stage, beginPhase(options_.progress, "maps"))) {
        Emission own = emitPhotonsFor(lead.scene, tracer, needs, b, 0);
        alone = true;
        ++emissions_;
        buildStage(own, own.budgets, true, s.stage);
      } else if (s.stage.fromPrefix) {
        ++prefixCuts_;
      }
    }
    if (!file.loaded) ++photonBuilds_;
    s.stage.buildSeconds += file.seconds;  // the one budget's file, read or written
    if (!file.note.empty()) s.stage.notes.push_back(file.note);
    s.buildCpuSeconds = build.cpuSeconds();
    s.cpuSeconds = s.buildCpuSeconds + sharedCpu;
    // Its share of the shared emission, as its emitSeconds (a budget emitted alone: in its build).
    if (!alone && emission.seconds > 0.0) {
      s.emitCpuSeconds = emittedCpu * std::min(1.0, s.stage.emitSeconds / emission.seconds);
    }
    s.seconds = build.wallSeconds() + shared;
    shared = sharedCpu = 0.0;
    s.prefixOf = s.stage.fromPrefix ? emission.budgets.total() : 0;
    for (const PlannedJob* j : jobs) {
      if (planBudgets(j->plan) == b) s.jobs.push_back(j);
    }
    visit(s);
  }
}

}  // namespace penumbra
