// Progress of penumbra render (issue 14 item 4): the phase line's ETA arithmetic,
// when the meter draws on a terminal and in a log, that every phase's counter
// reaches its total, and what the CLI prints with and without --quiet.
#include "plan/pipeline.h"
#include "cli/progress_line.h"
#include "cli/progress_meter.h"
#include "support/cli_run.h"
#include <gtest/gtest.h>
#include <cstdio>
#include <cstdlib>

using namespace penumbra;
using penumbra::testing::quote;
using penumbra::testing::runCli;
namespace pt = penumbra::testing;

namespace {

const std::string kScenes = std::string(PENUMBRA_SOURCE_DIR) + "/scenes/";

// Everything written to a tmpfile so far.
std::string contents(std::FILE* f) {
  std::fflush(f);
  std::rewind(f);
  std::string s;
  for (int c; (c = std::fgetc(f)) != EOF;) s.push_back(static_cast<char>(c));
  return s;
}

size_t count(const std::string& s, const std::string& what) {
  size_t n = 0;
  for (size_t at = s.find(what); at != std::string::npos; at = s.find(what, at + 1)) ++n;
  return n;
}

// A meter's output (a tmpfile) and the clock it reads, which the test moves.
struct Screen {
  std::FILE* out = std::tmpfile();
  double t = 100.0;
  ~Screen() { std::fclose(out); }
  ProgressDisplay display(bool terminal) {
    ProgressDisplay d;
    d.terminal = terminal;
    d.out = out;
    d.clock = [this] { return t; };
    return d;
  }
  std::string text() { return contents(out); }
};

}  // namespace

TEST(Progress, EtaExtrapolatesThePaceSoFar) {
  EXPECT_EQ(etaText(10.0, 0.0, 5.0), "ETA --");  // nothing done: no pace yet
  EXPECT_EQ(etaText(10.0, 2.0, 0.0), "done");
  EXPECT_EQ(etaText(90.0, 1.0, 1.0), "ETA 1:30");
  EXPECT_EQ(etaText(10.0, 0.25, 0.75), "ETA 0:30");
  // The sweep and batch line is unchanged by sharing the arithmetic.
  EXPECT_EQ(progressLine("sweep", 3, 8, "k50", "render 40%", 30.0, 2, 5),
            "sweep 3/8 | k50 | render 40% | 0:30 elapsed, ETA 1:15");
}

TEST(Progress, PhaseLineShowsBarPercentElapsedAndEta) {
  EXPECT_EQ(phaseLine("photons", 0.25, 10.0), "photons  [#####...............]  25% | 0:10 elapsed, ETA 0:30");
  EXPECT_EQ(phaseLine("maps", 1.0, 9.4), "maps     [####################] 100% | 0:09 elapsed, done");
  // A phase whose total is not known yet: no bar, no ETA, but the time moves.
  EXPECT_EQ(phaseLine("lookups", -1.0, 3.0), "lookups  [....................]   -- | 0:03 elapsed, ETA --");
  EXPECT_EQ(phaseLine("render", 2.0, 1.0).substr(0, 36), "render   [####################] 100%");
}

TEST(Progress, ALogGetsPlainLinesAtQuartersAndTheEnd) {
  Screen screen;
  double& t = screen.t;
  {
    ProgressMeter meter(screen.display(false));
    ProgressCounter* c = meter.begin("photons", 100);
    t += 0.3;
    meter.poll();  // younger than 0.5 s: silent
    EXPECT_EQ(screen.text(), "");
    t += 0.3;
    meter.poll();  // 0.6 s: the first line
    c->add(10);
    meter.poll();  // still the first quarter: no second line
    c->add(20);
    t += 0.4;
    meter.poll();  // 30%: the 25% line
    c->add(50);
    meter.poll();  // 80%: the 75% line
    meter.poll();
    t += 1.0;
    meter.begin("maps", 10);  // ends photons: its 100% line
    t += 0.2;
    meter.end();  // 0.2 s: never shown
    meter.finish();
  }
  const std::string log = screen.text();
  EXPECT_EQ(log.find('\r'), std::string::npos) << log;
  EXPECT_EQ(count(log, "\n"), 4u) << log;
  EXPECT_NE(log.find("photons  [....................]   0% | 0:01 elapsed, ETA --\n"), std::string::npos) << log;
  EXPECT_NE(log.find("photons  [######..............]  30% | 0:01 elapsed, ETA 0:02\n"), std::string::npos) << log;
  EXPECT_NE(log.find("  80% |"), std::string::npos) << log;
  EXPECT_NE(log.find("photons  [####################] 100% | 0:02 elapsed, done\n"), std::string::npos) << log;
  EXPECT_EQ(log.find("maps"), std::string::npos) << log;
}

TEST(Progress, ATerminalRedrawsOneLineInPlace) {
  Screen screen;
  {
    ProgressMeter meter(screen.display(true));
    for (ProgressCounter* c = meter.begin("render", 4); c->done < 4;) {
      screen.t += 0.25;
      c->add(1);
      meter.poll();  // every poll past 0.5 s redraws
    }
    meter.begin("short");
    meter.finish();
  }
  const std::string tty = screen.text();
  // 3 polls past 0.5 s; the end's 100% line is the last poll's, so not drawn again.
  EXPECT_EQ(count(tty, "\r\033[K"), 3u) << tty;
  EXPECT_EQ(count(tty, "\n"), 1u) << tty;        // the line closed once, at finish
  EXPECT_EQ(tty.back(), '\n');
  EXPECT_NE(tty.find("\r\033[Krender   [##########..........]  50% | 0:01 elapsed, ETA 0:01"), std::string::npos)
      << tty;
}

TEST(Progress, EveryPhaseCounterReachesItsTotal) {
  std::FILE* out = std::tmpfile();
  ProgressDisplay d;
  d.out = out;
  d.quietSeconds = 1e9;  // count, never draw
  ProgressMeter meter(d);
  RenderRequest req;
  req.scenePath = kScenes + "fig13_cornell_indirect.json";
  req.aov = "beauty";
  req.overrides = {"camera.width=40", "camera.height=30", "camera.spp=1", "photons.shadow=30000",
                   "photons.indirect=30000", "photons.gate=on", "photons.lookup=precomputed"};
  req.session.progress = &meter;
  const RenderResult r = runRender(req);
  meter.finish();
  std::vector<std::string> names;
  for (const auto& p : meter.ended()) {
    names.push_back(p.phase);
    EXPECT_GT(p.total, 0u) << p.phase;
    EXPECT_EQ(p.done, p.total) << p.phase;
  }
  ASSERT_EQ(names, (std::vector<std::string>{"photons", "maps", "lookups", "render"}));
  EXPECT_EQ(meter.ended()[0].total, r.stats.emitted[MapKind::Shadow] + r.stats.emitted[MapKind::Indirect]);
  EXPECT_EQ(meter.ended()[1].total, 2 * (r.stats.stored[MapKind::Shadow] + r.stats.stored[MapKind::Indirect]));
  EXPECT_EQ(meter.ended()[3].total, 3u * 2u);  // 16-pixel tiles over 40 x 30
  EXPECT_EQ(contents(out), "");
  std::fclose(out);
}

TEST(Progress, ProgressivePassesNameTheirPhases) {
  ProgressDisplay d;
  d.out = std::tmpfile();
  d.quietSeconds = 1e9;
  ProgressMeter meter(d);
  RenderRequest req;
  req.scenePath = kScenes + "cornell_physical.json";
  req.overrides = {"camera.width=32", "camera.height=32", "camera.spp=1", "photons.global=20000",
                   "photons.caustic=20000", "photons.passes=2"};
  req.session.progress = &meter;
  runRender(req);
  meter.finish();
  std::vector<std::string> names;
  for (const auto& p : meter.ended()) {
    names.push_back(p.phase);
    EXPECT_EQ(p.done, p.total) << p.phase;
  }
  EXPECT_EQ(names, (std::vector<std::string>{"photons", "maps", "render 1/2", "photons 2/2", "maps 2/2",
                                             "render 2/2"}));
  std::fclose(d.out);
}

TEST(Progress, CliPrintsPlainLinesInALogAndNothingWhenQuiet) {
  const pt::ScratchDir dir;
  const std::string scene = quote(kScenes + "fig03_shadows.json") +
                            " -D camera.width=48 -D camera.height=36 -D photons.shadow=20000";
  // Default threshold: a render this small shows no progress at all.
  const auto fast = runCli("render " + scene + " -o " + quote((dir / "a.png").string()));
  ASSERT_EQ(fast.exitCode, 0) << fast.err;
  EXPECT_EQ(fast.err.find("elapsed"), std::string::npos) << fast.err;

  setenv("PENUMBRA_PROGRESS_AFTER", "0", 1);  // every phase counts as long
  const auto log = runCli("render " + scene + " -o " + quote((dir / "b.png").string()));
  const auto quiet = runCli("render " + scene + " -q -o " + quote((dir / "c.png").string()));
  unsetenv("PENUMBRA_PROGRESS_AFTER");
  ASSERT_EQ(log.exitCode, 0) << log.err;
  EXPECT_EQ(log.err.find('\r'), std::string::npos) << log.err;  // stderr is a file: no redraws
  EXPECT_NE(log.err.find("photons  [####################] 100% | "), std::string::npos) << log.err;
  EXPECT_NE(log.err.find("\nmaps     [####################] 100% | "), std::string::npos) << log.err;
  EXPECT_NE(log.err.find("\nrender   [####################] 100% | "), std::string::npos) << log.err;
  EXPECT_EQ(log.out, "");  // the image path's stdout stays clean
  ASSERT_EQ(quiet.exitCode, 0) << quiet.err;
  EXPECT_EQ(quiet.err, "");
  // Progress changes no image byte.
  EXPECT_EQ(pt::readFile(dir / "a.png"), pt::readFile(dir / "b.png"));
  EXPECT_EQ(pt::readFile(dir / "a.png"), pt::readFile(dir / "c.png"));
}
