// What a sweep charges a run against what the run costs alone: a progressive run's
// total (every pass's photons and maps, shared stages in full) equals a lone
// render's --stats total of the same settings, compared in CPU seconds so a busy
// machine's waits do not enter either side.
#include "plan/cpu_report.h"
#include "plan/pipeline.h"
#include "plan/sweep/sweep_run.h"
#include "support/scratch_dir.h"
#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

namespace penumbra {
namespace {

const std::string kCornell = std::string(PENUMBRA_SOURCE_DIR) + "/scenes/cornell_physical.json";

// The lone render's --stats object, as `penumbra render --stats` writes it.
nlohmann::json standaloneStats(const std::vector<std::string>& overrides) {
  RenderRequest r;
  r.scenePath = kCornell;
  r.overrides = overrides;
  r.session.threads = 2;
  return nlohmann::json::parse(statsReport(runRender(r)));
}

// Six passes of 1.5e5 photons each: the later passes' photons are most of the work
// (a total without them would be ~40% short), and the run takes ~1.5 CPU-s, far
// above getrusage's resolution. Two k values share one budget's maps, so the second
// run reuses everything before its frame and is still charged it in full.
TEST(SweepCost, AProgressiveRunsTotalIsALoneRendersInCpuSeconds) {
  testing::ScratchDir dir;
  SweepRequest req;
  req.scenePath = kCornell;
  req.outDir = dir.path().string();
  req.spec = expandGrid({namedKnob("k", "40,80", physicalTransport())},
                        {"camera.width=96", "camera.height=72", "photons.global=150000", "photons.caustic=150000",
                         "photons.passes=6"});
  req.session.threads = 2;
  req.referencePasses = 1;
  req.compareGate = false;
  const SweepOutcome out = runSweep(req);
  ASSERT_EQ(out.rows.size(), 2u);
  EXPECT_EQ(out.totals.emissions, 1u) << "pass 0's photons emitted once for both runs";
  for (size_t i = 0; i < out.rows.size(); ++i) {
    const SweepRow& row = out.rows[i];
    const nlohmann::json alone = standaloneStats(req.spec.runs[i].overrides);
    const double cpu = alone.at("cpu_s").get<double>();
    EXPECT_NEAR(row.totalCpu, cpu, 0.10 * cpu) << row.id;
    // Every pass's photons are the run's, as the lone render counts them.
    const nlohmann::json& photons = alone.at("photons");
    EXPECT_EQ(row.photonsEmitted,
              photons.at("emitted_global").get<uint64_t>() + photons.at("emitted_caustic").get<uint64_t>())
        << row.id;
    EXPECT_GT(row.emit, 0.0) << row.id;
    EXPECT_GE(row.total, row.load + row.bvh + row.emit + row.maps + row.render - 1e-9) << row.id;
  }
}

}  // namespace
}  // namespace penumbra
