// What a sweep charges a run against what the run costs alone: a progressive run's
// total (every pass's photons and maps, shared stages in full) equals a lone
// render's --stats total of the same settings, compared in CPU seconds so a busy
// machine's waits do not enter either side; contended runs are ranked by CPU
// seconds, runs within the reference's noise are marked, and the up-front estimate
// charges what runs share once.
#include "plan/cost_model.h"
#include "plan/cpu_report.h"
#include "plan/pipeline.h"
#include "plan/render_session.h"
#include "plan/sweep/sweep_estimate.h"
#include "plan/sweep/sweep_report.h"
#include "plan/sweep/sweep_run.h"
#include "core/error.h"
#include "support/scratch_dir.h"
#include <gtest/gtest.h>
#include <cmath>
#include <nlohmann/json.hpp>
#include <fstream>

namespace penumbra {
namespace {

const std::string kCornell = std::string(PENUMBRA_SOURCE_DIR) + "/scenes/cornell_physical.json";

// The lone render's --stats object, as `penumbra render --stats` writes it.
nlohmann::json standaloneStats(const std::vector<std::string>& overrides) {
  RenderRequest r;
  r.scenePath = kCornell;
  r.overrides = overrides;
  r.session.threads = 1;
  return nlohmann::json::parse(statsReport(runRender(r)));
}

// Six passes of 1.5e5 photons each: the later passes' photons are most of the work
// (a total without them would be ~40% short), and the run takes ~1.5 CPU-s, far
// above getrusage's resolution. Two k values share one budget's maps, so the second
// run reuses everything before its frame and is still charged it in full. One
// thread: no idle worker spins into either account; on a busy machine the same
// work's CPU seconds still vary by a few percent (cache contention), so the lone
// renders run before and after the sweep, interleaved with it, and the nearer counts.
TEST(SweepCost, AProgressiveRunsTotalIsALoneRendersInCpuSeconds) {
  testing::ScratchDir dir;
  SweepRequest req;
  req.scenePath = kCornell;
  req.outDir = dir.path().string();
  req.spec = expandGrid({namedKnob("k", "40,80", physicalTransport())},
                        {"camera.width=96", "camera.height=72", "photons.global=150000", "photons.caustic=150000",
                         "photons.passes=6"});
  req.session.threads = 1;
  req.referencePasses = 1;
  req.compareGate = false;
  std::vector<nlohmann::json> before;
  for (const SweepRun& run : req.spec.runs) before.push_back(standaloneStats(run.overrides));
  const SweepOutcome out = runSweep(req);
  ASSERT_EQ(out.rows.size(), 2u);
  EXPECT_EQ(out.totals.emissions, 1u) << "pass 0's photons emitted once for both runs";
  for (size_t i = 0; i < out.rows.size(); ++i) {
    const SweepRow& row = out.rows[i];
    const nlohmann::json alone = standaloneStats(req.spec.runs[i].overrides);
    double cpu = alone.at("cpu_s").get<double>();
    const double earlier = before[i].at("cpu_s").get<double>();
    if (std::abs(earlier - row.totalCpu) < std::abs(cpu - row.totalCpu)) cpu = earlier;
    EXPECT_NEAR(row.totalCpu, cpu, 0.10 * cpu) << row.id << " (lone: " << earlier << " before, "
                                                << alone.at("cpu_s").get<double>() << " after)";
    // Every pass's photons are the run's, as the lone render counts them.
    const nlohmann::json& photons = alone.at("photons");
    EXPECT_EQ(row.photonsEmitted,
              photons.at("emitted_global").get<uint64_t>() + photons.at("emitted_caustic").get<uint64_t>())
        << row.id;
    EXPECT_GT(row.emit, 0.0) << row.id;
    EXPECT_GE(row.total, row.load + row.bvh + row.emit + row.maps + row.render - 1e-9) << row.id;
  }
}

// A results.csv from before total_cpu_s: the same knobs, other columns. The refusal
// names the version, not other knobs.
TEST(SweepCost, AnOlderResultsCsvIsRefusedAsAnotherVersions) {
  testing::ScratchDir dir;
  const std::vector<SweepKnob> knobs = {namedKnob("k", "40,80", physicalTransport())};
  std::string header = resultsCsv(knobs, {});
  header.replace(header.find(",total_cpu_s"), 12, "");
  std::ofstream(dir / "results.csv") << header << "k=40,40,0\n";
  try {
    readFinishedRows((dir / "results.csv").string(), knobs);
    FAIL() << "an older results.csv was read";
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find("written by another version of penumbra"), std::string::npos) << e.what();
  }
}

// The contended pair: k 20 "cost" 12.9 s of wall against 6.9 s for k 100,
// where CPU time says 1.1 against 1.6 s and k 20 is also the more accurate.
std::vector<SweepRow> contendedPair(double share) {
  auto row = [share](const char* id, double wall, double cpu, double relMse) {
    SweepRow r;
    r.id = id;
    r.values = {};
    r.total = r.spent = wall;
    r.totalCpu = cpu;
    r.cpuShare = share;
    r.relMse = relMse;
    r.rmse = 0.05;
    return r;
  };
  return {row("k=20", 12.9, 1.1, 0.0067), row("k=100", 6.9, 1.6, 0.0076)};
}

TEST(SweepCost, ContendedRunsAreRankedByCpuSecondsAndTheReportSaysSo) {
  const std::vector<SweepRow> quiet = contendedPair(0.95), busy = contendedPair(0.3);
  EXPECT_FALSE(contendedRows(quiet));
  EXPECT_TRUE(contendedRows(busy));
  EXPECT_EQ(paretoFront(quiet, SweepMetric::RelMse, SweepCost::Wall), (std::vector<size_t>{1, 0}));
  EXPECT_EQ(paretoFront(busy, SweepMetric::RelMse, SweepCost::Cpu), (std::vector<size_t>{0}));
  const std::string calm = reportMarkdown("scene", SweepSpec{}, quiet, SweepTotals{});
  EXPECT_NE(calm.find("cost is wall time (`total_s`)"), std::string::npos) << calm;
  const std::string md = reportMarkdown("scene", SweepSpec{}, busy, SweepTotals{});
  EXPECT_NE(md.find("cost is CPU seconds (`total_cpu_s`)"), std::string::npos) << md;
  EXPECT_NE(md.find("The cheapest (in CPU seconds) run"), std::string::npos) << md;
  const size_t front = md.find("## Pareto front"), reach = md.find("## Time to reach");
  ASSERT_LT(front, reach);
  const std::string frontRows = md.substr(front, reach - front);
  EXPECT_NE(frontRows.find("| 12.900 | 1.100 |"), std::string::npos) << frontRows;
  EXPECT_EQ(frontRows.find("| 6.900 | 1.600 |"), std::string::npos) << frontRows;
}

// A reference with ~0.01 RMSE of its own noise: a run measured at 0.012 cannot be told
// from a perfect one (its own error is at most ~0.0066), one at 0.02 can.
TEST(SweepCost, RunsWithinTheReferencesNoiseAreMarked) {
  std::vector<SweepRow> rows = contendedPair(0.95);
  rows[0].rmse = 0.012;
  rows[1].rmse = 0.02;
  EXPECT_TRUE(withinReferenceNoise(rows[0], 0.01));
  EXPECT_FALSE(withinReferenceNoise(rows[1], 0.01));
  EXPECT_FALSE(withinReferenceNoise(rows[0], -1.0)) << "no figure, no mark";
  SweepTotals t;
  t.referenceNoiseRmse = 0.01;
  const std::string md = reportMarkdown("scene", SweepSpec{}, rows, t);
  EXPECT_NE(md.find("is marked `~ref` (1 of 2 runs)"), std::string::npos) << md;
  EXPECT_NE(md.find("it is not measurably better"), std::string::npos) << md;  // the best run is the marked one
  EXPECT_NE(md.find("| 0.012 | 0.0067 | 0.00 | 0 | ~ref |"), std::string::npos) << md;
}

// Two runs on one photon budget (k differs) and one on a smaller budget: pass 0's
// photons are charged once per budget, later passes per run, the BVH once, and the
// runs' shares (the ETA's steps) add up to the whole; the long reference is the
// highest run at its passes times the factor.
TEST(SweepCost, TheEstimateChargesSharedStagesOnce) {
  RenderSession session([] {
    SessionOptions o;
    o.threads = 2;
    return o;
  }());
  auto planned = [&](const std::string& photons, const std::string& k) {
    JobRequest r;
    r.scenePath = kCornell;
    r.overrides = {"camera.width=32", "camera.height=32", "photons.passes=3", "photons.global=" + photons,
                   "photons.caustic=" + photons, "photons.k_global=" + k};
    PlannedJob job = session.plan(r);
    session.prepare(job);
    return job;
  };
  const PlannedJob a = planned("20000", "10"), b = planned("20000", "40"), c = planned("5000", "10");
  SweepEstimateInput in;
  in.runs = {&a, &b, nullptr, &c};
  in.reference = &b;
  in.referencePasses = 4;
  const SweepEstimate e = estimateSweep(in);
  const ResourceEstimate& ea = a.admission.estimate;
  const ResourceEstimate& ec = c.admission.estimate;
  ASSERT_EQ(ea.plan.photonPasses, 3);
  const double passA = ea.photonSeconds / 3, passC = ec.photonSeconds / 3;
  EXPECT_NEAR(e.photons, passA + 2 * (2 * passA) + passC + 2 * passC, 1e-9 * e.photons);
  EXPECT_LT(e.photons, 2 * ea.photonSeconds + ec.photonSeconds);
  EXPECT_EQ(e.runs[2], 0.0);
  EXPECT_NEAR(e.runs[0] + e.runs[1] + e.runs[3], e.bvh + e.photons + e.frames, 1e-9 * e.seconds());
  const double frame = b.admission.estimate.renderSeconds - b.admission.estimate.bvhSeconds - cost::kStartupSeconds;
  EXPECT_NEAR(e.reference, passA * 12 + frame * 4, 1e-9 * e.reference);
  // Two threads joining ten runnable tasks on two cores get a sixth of a core each.
  EXPECT_DOUBLE_EQ(busyStretch(10.0, 2, 2), 6.0);
  EXPECT_DOUBLE_EQ(busyStretch(0.0, 2, 2), 1.0);
  EXPECT_DOUBLE_EQ(busyStretch(-1.0, 2, 2), 1.0) << "load unknown";
  SweepEstimate busy = e;
  busy.stretch = 6.0;
  EXPECT_NE(describeSweepEstimate(busy, 3, 2, 10.0, 2).find("the machine is busy (load 10.0 on 2 cores)"),
            std::string::npos);
  EXPECT_EQ(describeSweepEstimate(e, 3, 2).find("busy"), std::string::npos);
}

}  // namespace
}  // namespace penumbra
