// The sweep's up-front estimate from its runs' own (plan/sweep/sweep_estimate.h).
#include "plan/sweep/sweep_estimate.h"
#include "plan/cost_model.h"
#include "plan/render_session.h"
#include "plan/transport_model.h"
#include <fmt/format.h>
#include <algorithm>
#include <map>

namespace penumbra {
namespace {

// A run's photon seconds split as the sweep spends them: pass 0's (shared by every
// run of its budget) and every later pass's own.
struct PhotonShare {
  double first = 0.0, later = 0.0;
};

PhotonShare photonShare(const ResourceEstimate& e) {
  const double perPass = e.photonSeconds / std::max(e.plan.photonPasses, 1);
  return {perPass, e.photonSeconds - perPass};
}

// The frames alone: the estimate's render less the BVH and the start-up a sweep pays once.
double frameSeconds(const ResourceEstimate& e) {
  return std::max(0.0, e.renderSeconds - e.bvhSeconds - cost::kStartupSeconds);
}

}  // namespace

SweepEstimate estimateSweep(const SweepEstimateInput& in) {
  SweepEstimate out;
  out.runs.assign(in.runs.size(), 0.0);
  // Shared stages: per geometry its BVH, per (photon key, pass-0 budget) its photons;
  // each split evenly over the runs that share it.
  std::map<std::string, std::vector<size_t>> byGeometry;
  std::map<std::pair<std::string, std::string>, std::vector<size_t>> byBudget;
  for (size_t i = 0; i < in.runs.size(); ++i) {
    const PlannedJob* j = in.runs[i];
    if (!j) continue;
    byGeometry[j->keys.geometry].push_back(i);
    const MapCounts b = planBudgets(j->plan);
    std::string budget;
    for (uint64_t n : b.values) budget += std::to_string(n) + ",";
    byBudget[{j->keys.geometry + "\n" + j->keys.photons, budget}].push_back(i);
  }
  for (const auto& [key, runs] : byGeometry) {
    const double s = in.runs[runs.front()]->admission.estimate.bvhSeconds + cost::kStartupSeconds;
    out.bvh += s;
    for (size_t i : runs) out.runs[i] += s / double(runs.size());
  }
  for (const auto& [key, runs] : byBudget) {
    const double s = photonShare(in.runs[runs.front()]->admission.estimate).first;
    out.photons += s;
    for (size_t i : runs) out.runs[i] += s / double(runs.size());
  }
  for (size_t i = 0; i < in.runs.size(); ++i) {
    const PlannedJob* j = in.runs[i];
    if (!j) continue;
    const Admission& a = j->admission;
    const ResourceEstimate& e = a.estimate;
    const PhotonShare p = photonShare(e);
    // A budget's passes: at most what its bound allows (plan/job_admission.h).
    double frames = a.budget.any() ? std::max(0.0, a.budgetSeconds - e.bvhSeconds - cost::kStartupSeconds - p.first - p.later)
                                   : frameSeconds(e);
    frames *= in.repeat + (in.compareGate && j->plan[Pass::Gate].on ? 1 : 0);
    out.photons += p.later;
    out.frames += frames;
    out.runs[i] += p.later + frames;
  }
  if (in.reference) {
    // The highest run with referencePasses times its passes, each with fresh photons
    // where the model emits them per pass.
    const ResourceEstimate& e = in.reference->admission.estimate;
    const bool fresh = transportOf(in.reference->scene).freshPhotonsEachPass();
    const double passes = double(std::max(e.plan.passes, 1)) * in.referencePasses;
    out.reference = photonShare(e).first * (fresh ? passes : 1.0) + frameSeconds(e) * in.referencePasses;
  }
  return out;
}

namespace {
// Short parts keep a decimal: a small sweep's parts are seconds.
std::string duration(double s) { return s < 10.0 ? fmt::format("{:.1f} s", s) : formatDuration(s); }
}  // namespace

double busyStretch(double load, int cores, int threads) {
  if (load < 0.0 || cores <= 0) return 1.0;
  return std::max(1.0, (load + threads) / cores);
}

std::string describeSweepEstimate(const SweepEstimate& e, size_t runs, int threads, double load, int cores) {
  const std::string reference = e.reference > 0.0 ? fmt::format("reference ~{}, ", duration(e.reference)) : "";
  std::string line = fmt::format("sweep: {} run{} to render, estimated ~{} on {} thread{} ({}photons ~{}, frames ~{})",
                                 runs, runs == 1 ? "" : "s", duration(e.seconds()), threads, threads == 1 ? "" : "s",
                                 reference, duration(e.photons), duration(e.frames + e.bvh));
  // Below 1.5 the load's own noise is as large as the stretch.
  if (e.stretch >= 1.5) {
    line += fmt::format("; the machine is busy (load {:.1f} on {} cores): ~{}", load, cores,
                        duration(e.seconds() * e.stretch));
  }
  return line;
}

}  // namespace penumbra
