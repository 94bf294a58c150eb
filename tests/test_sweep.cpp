// penumbra sweep against independent renders: every run's image equals a plain
// runRender of the same settings (byte for byte at the largest photon budget,
// within the power packing's rounding for prefix-cut budgets), a rerun resumes
// without rendering, the gate's trade-off is measured, and bad runs fail first.
#include "plan/pipeline.h"
#include "plan/sweep/sweep_report.h"
#include "plan/sweep/sweep_run.h"
#include "core/error.h"
#include "io/image_compare.h"
#include "io/image_io.h"
#include "support/cli_run.h"
#include <gtest/gtest.h>
#include <fmt/format.h>
#include <filesystem>
#include <fstream>
#include <csignal>
#include <sys/wait.h>

namespace penumbra {
namespace {

namespace fs = std::filesystem;
const std::string kCornell = std::string(PENUMBRA_SOURCE_DIR) + "/scenes/cornell_physical.json";
const std::string kShadows = std::string(PENUMBRA_SOURCE_DIR) + "/scenes/fig03_shadows.json";

SweepRequest cornellSweep(const std::string& dir) {
  const std::vector<std::string> base = {"camera.width=48", "camera.height=48"};
  SweepRequest req;
  req.scenePath = kCornell;
  req.outDir = dir;
  req.spec = expandGrid({namedKnob("photons", "3e3,2e4", physicalTransport()),
                         namedKnob("k", "8,40", physicalTransport()),
                         namedKnob("spp", "1,2", physicalTransport())},
                        base);
  req.session.threads = 2;
  req.referencePasses = 1;  // the highest run is the reference row
  return req;
}

// A plain render of the same settings, through the same EXR writer as the sweep's images.
Image standalone(const std::string& scene, const std::vector<std::string>& overrides, const fs::path& exr) {
  RenderRequest r;
  r.scenePath = scene;
  r.overrides = overrides;
  r.session.threads = 2;
  r.outputPath = exr.string();
  runRender(r);
  return readImage(exr.string());
}

TEST(Sweep, GridExpandsEveryCombinationWithIntegerCounts) {
  SweepSpec spec = expandGrid({namedKnob("photons", "1e4,1e5", classicTransport()),
                               namedKnob("depth", "1,8,4", classicTransport())},
                              {"camera.spp=1"});
  ASSERT_EQ(spec.runs.size(), 6u);
  EXPECT_EQ(spec.runs[0].id, "photons=1e4 depth=1");
  EXPECT_EQ(spec.runs[0].overrides,
            (std::vector<std::string>{"camera.spp=1", "photons.indirect=10000", "render.max_depth=1"}));
  EXPECT_EQ(spec.runs[spec.highest].id, "photons=1e5 depth=8");  // numeric, not the last listed
  EXPECT_THROW(expandGrid({namedKnob("spp", "1,2", classicTransport()), keyKnob("camera.spp=3")}, {}),
               InputError);
  EXPECT_THROW(keyKnob("photons.k_shadow"), InputError);
  EXPECT_THROW(splitValues("1,,2", "--k"), InputError);
}

TEST(Sweep, ParetoFrontKeepsOnlyUnbeatenRuns) {
  auto row = [](double t, double e) { SweepRow r; r.total = t; r.rmse = e; return r; };
  std::vector<SweepRow> rows = {row(1, 0.5), row(2, 0.2), row(3, 0.3), row(4, 0.1), row(2, 0.4)};
  SweepRow ref = row(9, 0.0);
  ref.reference = true;
  rows.push_back(ref);
  EXPECT_EQ(paretoFront(rows, SweepMetric::Rmse), (std::vector<size_t>{0, 1, 3}));
}

TEST(Sweep, TheMetricDecidesTheFrontAndTheBestRun) {
  // The README's case: a run whose RMSE a few hot caustic pixels dominate, against a
  // blotchier one with the lower RMSE but ten times the relMSE and 15 dB less PSNR.
  auto row = [](double t, double rmse, double relMse, double psnr) {
    SweepRow r;
    r.id = "run at " + std::to_string(t) + " s";  // the report lists finished rows, those with an id
    r.total = t;
    r.rmse = rmse;
    r.relMse = relMse;
    r.psnr = psnr;
    return r;
  };
  const std::vector<SweepRow> rows = {row(20, 0.066, 0.00099, 42.5), row(10, 0.048, 0.0096, 27.6)};
  EXPECT_EQ(bestRun(rows, SweepMetric::RelMse), 0u);
  EXPECT_EQ(bestRun(rows, SweepMetric::Psnr), 0u);
  EXPECT_EQ(bestRun(rows, SweepMetric::RmseClamped), 0u);
  EXPECT_EQ(bestRun(rows, SweepMetric::Rmse), 1u);
  EXPECT_EQ(paretoFront(rows, SweepMetric::Rmse), (std::vector<size_t>{1}));
  EXPECT_EQ(paretoFront(rows), (std::vector<size_t>{1, 0}));
  const std::string md = reportMarkdown("scene", SweepSpec{}, rows, SweepTotals{});
  EXPECT_NE(md.find("## Best run"), std::string::npos);
  // Time to reach: relMSE 0.002 first at the 20 s run, 0.01 already at the 10 s one.
  EXPECT_NE(md.find("| 0.002 | 20.000 |"), std::string::npos) << md;
  EXPECT_NE(md.find("| 0.01 | 10.000 |"), std::string::npos) << md;
  EXPECT_EQ(parseMetric("rmse-clamped"), SweepMetric::RmseClamped);
  EXPECT_THROW(parseMetric("mse"), InputError);
}

TEST(Sweep, RunsEqualStandaloneRendersAndRerunsResume) {
  testing::ScratchDir dir;
  SweepRequest req = cornellSweep(dir.path().string());
  SweepOutcome first = runSweep(req);
  ASSERT_EQ(first.rows.size(), 8u);
  EXPECT_EQ(first.totals.emissions, 1u) << "one emission, the smaller budget cut out of it";
  EXPECT_EQ(first.totals.prefixCuts, 1u);
  EXPECT_EQ(first.totals.mapBuilds, 2u);
  EXPECT_EQ(first.totals.bvhBuilds, 1u);
  const Image reference = readImage((dir / "reference.exr").string());
  for (size_t i = 0; i < first.rows.size(); ++i) {
    const SweepRow& row = first.rows[i];
    const Image swept = readImage((dir / row.image).string());
    const Image alone = standalone(kCornell, req.spec.runs[i].overrides, dir / "alone.exr");
    const ImageError diff = compareImages(swept, alone);
    if (row.values[0] == "2e4") {
      // Full budget: the same photons, maps and samples.
      EXPECT_EQ(diff.maxError, 0.0) << row.id;
    } else {
      // A prefix: powers repacked (2^-8) -> far below the run's own error.
      EXPECT_LT(diff.rmse, 0.02 * row.rmse) << row.id;
    }
    EXPECT_NEAR(row.rmse, compareImages(swept, reference).rmse, 1e-3 * row.rmse + 1e-6) << row.id;
    EXPECT_EQ(row.reference, row.id == "photons=2e4 k=40 spp=2");
    // Its header says what the lone render's does, and which run it is.
    const std::string runPath = (dir / row.image).string(), alonePath = (dir / "alone.exr").string();
    EXPECT_EQ(readImageAttribute(runPath, "penumbra:sweep_run"), row.id);
    for (const char* key : {"penumbra:settings", "penumbra:spp", "penumbra:photons.global", "penumbra:plan"})
      EXPECT_EQ(readImageAttribute(runPath, key), readImageAttribute(alonePath, key)) << row.id << ": " << key;
  }
  // More photons, k and samples: the cheapest run is the worst.
  EXPECT_GT(first.rows.front().rmse, first.rows[6].rmse);

  const auto written = fs::last_write_time(dir / first.rows[0].image);
  SweepOutcome again = runSweep(req);
  EXPECT_EQ(again.totals.resumed, 8u);
  EXPECT_EQ(again.totals.emissions, 0u);
  EXPECT_EQ(fs::last_write_time(dir / first.rows[0].image), written);
  ASSERT_EQ(again.rows.size(), 8u);
  EXPECT_EQ(again.rows[3].rmse, std::stod(fmt::format("{:.6g}", first.rows[3].rmse)));
  EXPECT_TRUE(fs::exists(dir / "report.md"));
}

// --repeat renders each frame again on its maps: the same image, the fastest time kept
// beside the median, and each run's own error estimate beside its measured error.
TEST(Sweep, RepeatsKeepTheFastestAndTheMedianAndEveryRunItsEstimate) {
  testing::ScratchDir dir;
  SweepRequest req;
  req.scenePath = kCornell;
  req.outDir = dir.path().string();
  req.spec = expandGrid({namedKnob("spp", "2,4", physicalTransport())},
                        {"camera.width=32", "camera.height=32", "photons.global=3000", "photons.caustic=3000"});
  req.session.threads = 2;
  req.repeat = 3;
  const SweepOutcome out = runSweep(req);
  ASSERT_EQ(out.rows.size(), 2u);
  for (const SweepRow& row : out.rows) {
    EXPECT_GT(row.render, 0.0) << row.id;
    EXPECT_LE(row.render, row.renderMedian) << row.id;
    EXPECT_GT(row.noiseRmse, 0.0) << row.id << ": spp >= 2 has a spread";
  }
  const Image alone = standalone(kCornell, req.spec.runs[0].overrides, dir / "alone.exr");
  EXPECT_EQ(compareImages(readImage((dir / out.rows[0].image).string()), alone).maxError, 0.0);
  const std::string report = testing::readFile(dir / "report.md");
  EXPECT_NE(report.find("rendered 3 times"), std::string::npos) << report;
  EXPECT_NE(report.find("Its own error estimate"), std::string::npos) << report;
}

// Without --reference the sweep renders the highest run with 8x its passes, says
// how far that render is from converged, and a rerun reloads it.
TEST(Sweep, TheDefaultReferenceIsALongerProgressiveRenderWithItsOwnEstimate) {
  testing::ScratchDir dir;
  SweepRequest req;
  req.scenePath = kCornell;
  req.outDir = (dir / "out").string();
  const std::vector<std::string> base = {"camera.width=24", "camera.height=24", "photons.global=2000",
                                         "photons.caustic=2000", "photons.passes=2"};
  req.spec = expandGrid({namedKnob("spp", "1,2", physicalTransport())}, base);
  req.session.threads = 2;
  const SweepOutcome out = runSweep(req);
  for (const SweepRow& row : out.rows) EXPECT_FALSE(row.reference) << row.id;
  std::vector<std::string> longer = req.spec.runs[req.spec.highest].overrides;
  longer.push_back("photons.passes=16");
  const Image alone = standalone(kCornell, longer, dir / "alone.exr");
  const Image reference = readImage((dir / "out" / "reference.exr").string());
  EXPECT_EQ(compareImages(reference, alone).maxError, 0.0);
  EXPECT_NEAR(out.rows[1].rmse, compareImages(readImage((dir / "out" / out.rows[1].image).string()), alone).rmse,
              1e-3 * out.rows[1].rmse);
  const std::string report = testing::readFile(dir / "out" / "report.md");
  EXPECT_NE(report.find("16 passes of the run at every knob's highest value (spp=2)"), std::string::npos) << report;
  EXPECT_NE(report.find("Its own error estimate, how far it is from converged: ~"), std::string::npos) << report;
  EXPECT_NE(report.find("from 16 passes"), std::string::npos) << report;
  const auto written = fs::last_write_time(dir / "out" / "reference.exr");
  const SweepOutcome again = runSweep(req);
  EXPECT_EQ(fs::last_write_time(dir / "out" / "reference.exr"), written) << "reloaded, not rendered again";
  EXPECT_NE(again.totals.referenceNote.find("reloaded"), std::string::npos) << again.totals.referenceNote;
  EXPECT_NE(again.totals.referenceNote.find("from 16 passes"), std::string::npos) << again.totals.referenceNote;
}

// --threads 1,2: every run at each count, in its own session; the images are the same
// pixels (deterministic), each row's CPU share is of its own count, and the idle-knob
// check leaves the thread count alone.
TEST(Sweep, AThreadsListRendersEveryRunAtEachCountWithTheSamePixels) {
  testing::ScratchDir dir;
  SweepRequest req;
  req.scenePath = kCornell;
  req.outDir = dir.path().string();
  req.referencePasses = 1;
  req.spec = expandGrid({namedKnob("spp", "1,2", physicalTransport()), threadsKnob("1,2")},
                        {"camera.width=24", "camera.height=24", "photons.global=2000", "photons.caustic=2000"});
  EXPECT_EQ(threadCounts(req.spec), (std::vector<int>{2, 1}));
  const SweepOutcome out = runSweep(req);
  ASSERT_EQ(out.rows.size(), 4u);
  EXPECT_EQ(out.rows[0].id, "spp=1 threads=1");
  for (size_t i = 0; i < 4; i += 2) {
    const Image one = readImage((dir / out.rows[i].image).string());
    const Image two = readImage((dir / out.rows[i + 1].image).string());
    EXPECT_EQ(compareImages(one, two).maxError, 0.0) << out.rows[i].id;
    EXPECT_GT(out.rows[i].cpuShare, 0.0);
  }
  EXPECT_TRUE(out.rows[3].reference);
  for (const std::string& n : out.notes) EXPECT_EQ(n.find("knob threads"), std::string::npos) << n;
  EXPECT_EQ(out.totals.bvhBuilds, 2u) << "one session per thread count";
  const std::string csv = testing::readFile(dir / "results.csv");
  EXPECT_NE(csv.find("spp=1 threads=2"), std::string::npos);
  EXPECT_THROW(threadsKnob("1,0"), InputError);
  EXPECT_THROW(threadsKnob("2x"), InputError);
}

// Two lights of equal power, one shut in a black box: the plan splits the global
// photons by reach (all to the free light) in every progressive pass, in the sweep
// as in a lone render.
TEST(Sweep, RunsSplitTheirLightsByReachInEveryPassAsALoneRenderDoes) {
  testing::ScratchDir dir;
  const std::string scene = (dir / "boxed.json").string();
  std::ofstream(scene) << R"({
    "camera": {"position": [0, 2, 4], "look_at": [0, 0, 0], "fov": 50, "width": 32, "height": 24},
    "materials": {"grey": {"diffuse": 0.6}, "black": {"diffuse": 0}},
    "lights": [{"type": "point", "position": [0, 1.5, 0], "intensity": 5},
               {"type": "point", "position": [3, 1, -3], "intensity": 5}],
    "objects": [{"type": "quad", "corner": [-4, 0, 4], "edge1": [8, 0, 0], "edge2": [0, 0, -8], "material": "grey"},
                {"type": "quad", "corner": [-4, 0, -2], "edge1": [8, 0, 0], "edge2": [0, 3, 0], "material": "grey"},
                {"type": "box", "min": [2.5, 0.5, -3.5], "max": [3.5, 1.5, -2.5], "material": "black"}],
    "render": {"model": "physical", "seed": 3},
    "photons": {"global": 4000, "caustic": 0, "k_global": 20, "passes": 2}
  })";
  SweepRequest req;
  req.scenePath = scene;
  req.outDir = (dir / "out").string();
  req.spec = expandGrid({namedKnob("spp", "1,2", physicalTransport())}, {});
  req.session.threads = 2;
  const SweepOutcome out = runSweep(req);
  ASSERT_EQ(out.rows.size(), 2u);
  for (size_t i = 0; i < out.rows.size(); ++i) {
    const Image swept = readImage((dir / "out" / out.rows[i].image).string());
    const Image alone = standalone(scene, req.spec.runs[i].overrides, dir / "alone.exr");
    EXPECT_EQ(compareImages(swept, alone).maxError, 0.0) << out.rows[i].id;
  }
}

TEST(Sweep, GatedRunsReportTheRaysAvoidedAndTheErrorTheGateAdds) {
  testing::ScratchDir dir;
  SweepRequest req;
  req.scenePath = kShadows;
  req.outDir = dir.path().string();
  req.spec = expandGrid({keyKnob("photons.shadow=2e4,1e5")},
                        {"camera.width=64", "camera.height=48", "photons.gate=on"});
  req.session.threads = 2;
  SweepOutcome out = runSweep(req);
  ASSERT_EQ(out.rows.size(), 2u);
  for (const SweepRow& r : out.rows) {
    EXPECT_TRUE(r.gate) << r.id;
    EXPECT_GT(r.shadowRaysAvoided, 0u) << r.id;
    EXPECT_EQ(r.shadowRays + r.shadowRaysAvoided, r.ungatedShadowRays) << r.id;
    EXPECT_LT(r.gateRmse, 0.05) << r.id;
  }
  EXPECT_EQ(out.totals.prefixCuts, 1u) << "2e4 shadow photons cut out of the 1e5 emission";
}

// Ctrl-C mid-sweep: results.csv keeps every finished row (each with its image),
// nothing half-written is left, and a rerun renders only what is missing. The
// binary's test hook raises SIGINT while the fourth results.csv (header + 3 rows) is
// being written, so the file on disk holds exactly the first two rows.
TEST(Sweep, SigintLeavesEveryFinishedRowAndNoPartialFile) {
  testing::ScratchDir dir;
  const fs::path out = dir / "sweep";
  const std::string scene = std::string(PENUMBRA_SOURCE_DIR) + "/scenes/fig01_depth.json";
  const int status = testing::runCliSignalledAt(
      "temp-file:results.tmp:4", {"sweep", scene, "-o", out.string(), "-q", "--spp", "1,2,3,4,5,6", "--set",
                                  "camera.width=96", "--set", "camera.height=96"});
  ASSERT_TRUE(WIFSIGNALED(status) && WTERMSIG(status) == SIGINT)
      << "status " << status << ": the hook did not interrupt the sweep";
  for (const auto& e : fs::recursive_directory_iterator(out)) {
    EXPECT_EQ(e.path().filename().string().find(".tmp"), std::string::npos) << e.path();
  }
  const std::vector<SweepKnob> knobs = {namedKnob("spp", "1,2,3,4,5,6", classicTransport())};
  const auto rows = readFinishedRows((out / "results.csv").string(), knobs);
  ASSERT_EQ(rows.size(), 2u);
  for (const auto& [id, row] : rows) EXPECT_TRUE(fs::exists(out / row.image)) << id;
  SweepRequest again;
  again.scenePath = scene;
  again.outDir = out.string();
  again.spec = expandGrid(knobs, {"camera.width=96", "camera.height=96"});
  const SweepOutcome resumed = runSweep(again);
  EXPECT_EQ(resumed.totals.resumed, rows.size());
  EXPECT_EQ(resumed.rows.size(), 6u);
}

TEST(Sweep, ABadRunFailsBeforeAnyRender) {
  testing::ScratchDir dir;
  SweepRequest req = cornellSweep(dir.path().string());
  req.spec = expandGrid({keyKnob("render.max_depth=2,-3")}, {"camera.width=16", "camera.height=16"});
  try {
    runSweep(req);
    FAIL() << "expected an InputError";
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find("sweep run 'render.max_depth=-3'"), std::string::npos) << e.what();
  }
  EXPECT_FALSE(fs::exists(dir / "runs"));
  EXPECT_FALSE(fs::exists(dir / "results.csv"));
}

TEST(Sweep, AFailedSweepLeavesNoFileThatBlocksARetryWithOtherKnobs) {
  // A reference of the wrong size fails the sweep; the same folder then takes a
  // sweep of other knobs, since the failed one finished no run.
  testing::ScratchDir dir;
  writeImage((dir / "small.exr").string(), Image(8, 8));
  SweepRequest req = cornellSweep(dir.path().string());
  const std::vector<std::string> base = {"camera.width=16", "camera.height=16"};
  req.spec = expandGrid({keyKnob("render.max_depth=1,2")}, base);
  req.referencePath = (dir / "small.exr").string();
  EXPECT_THROW(runSweep(req), InputError);
  req.spec = expandGrid({keyKnob("camera.spp=1,2")}, base);
  req.referencePath.clear();
  EXPECT_NO_THROW(runSweep(req));
  std::ifstream csv(dir / "results.csv");
  std::string header;
  ASSERT_TRUE(std::getline(csv, header));
  EXPECT_NE(header.find("camera.spp"), std::string::npos) << header;
}

TEST(Sweep, AKnobThatChangesNothingIsSaidWithItsReason) {
  // fig03's one point light: gate auto turns the gate off, so photons.shadow changes
  // no pixel; spp does.
  testing::ScratchDir dir;
  SweepRequest req = cornellSweep(dir.path().string());
  req.scenePath = kShadows;
  req.spec = expandGrid({keyKnob("photons.shadow=1e3,1e4"), keyKnob("camera.spp=1,2")},
                        {"camera.width=16", "camera.height=16"});
  const SweepOutcome out = runSweep(req);
  std::string notes;
  for (const std::string& n : out.notes) notes += n + "\n";
  EXPECT_NE(notes.find("knob photons.shadow changed nothing: its runs rendered identical images (the gate was off"),
            std::string::npos) << notes;
  EXPECT_EQ(notes.find("knob camera.spp"), std::string::npos) << notes;
  // The contact sheet: four 192-pixel tiles in a row, 6-pixel gaps.
  const Image sheet = readImage((dir / "runs.png").string());
  EXPECT_EQ(sheet.width, 4 * (192 + 6) + 6);
}

}  // namespace
}  // namespace penumbra
