// CPU time beside wall time, from figures given rather than measured where a
// measurement would race: the share and the contended note, the load average read
// from a file, a span over CPU work counted by the thread's own CPU clock, the
// bench's thread list, min and median, and its table from a synthetic outcome.
#include "core/cpu_time.h"
#include "core/error.h"
#include "plan/bench_report.h"
#include "plan/bench_run.h"
#include "plan/cpu_report.h"
#include "support/scratch_dir.h"
#include <gtest/gtest.h>
#include <nlohmann/json.hpp>
#include <time.h>

namespace penumbra {
namespace {

TEST(CpuTime, ShareIsCpuOverWallTimesThreads) {
  const CpuTiming half = cpuTiming(2.0, 2.0, 2, 0.5);
  EXPECT_DOUBLE_EQ(half.share, 0.5);
  EXPECT_TRUE(half.contended());
  const CpuTiming busy = cpuTiming(2.0, 3.8, 2, 0.5);
  EXPECT_DOUBLE_EQ(busy.share, 0.95);
  EXPECT_FALSE(busy.contended());
  // Exactly at the threshold is not contended; an empty or a short span is not judged.
  EXPECT_FALSE(cpuTiming(1.0, kContendedShare, 1, 0.0).contended());
  EXPECT_FALSE(cpuTiming(0.0, 0.0, 2, -1.0).contended());
  EXPECT_FALSE(cpuTiming(0.1, 0.02, 2, 0.0).contended());
  EXPECT_TRUE(cpuTiming(kShortestJudgedSeconds, 0.2, 2, 0.0).contended());
  EXPECT_DOUBLE_EQ(cpuTiming(0.0, 0.0, 2, -1.0).share, 0.0);
}

TEST(CpuTime, ContendedNoteSaysWhichSpansAndTheLowestShare) {
  EXPECT_EQ(contendedNote({cpuTiming(1.0, 1.95, 2, 0.1)}, "render"), "");
  const std::string one = contendedNote({cpuTiming(1.0, 1.0, 2, 1.5)}, "render");
  EXPECT_NE(one.find("times are contended: the render's CPU share was 0.50 of 2 threads, load 1.50 at start"),
            std::string::npos) << one;
  EXPECT_EQ(one.find('\n'), std::string::npos) << "one line";
  const std::string some = contendedNote(
      {cpuTiming(1.0, 1.9, 2, 0.2), cpuTiming(1.0, 1.2, 2, 0.4), cpuTiming(1.0, 0.7, 1, -1.0)}, "run");
  EXPECT_NE(some.find("2 of 3 runs had a CPU share below 0.9 (lowest 0.60 of 2 threads, load 0.40 at start)"),
            std::string::npos) << some;
}

TEST(CpuTime, CpuFieldsAndLineCarryTheFigures) {
  nlohmann::json j;
  addCpuFields(j, cpuTiming(2.0, 3.0, 2, 0.25));
  EXPECT_DOUBLE_EQ(j["cpu_s"].get<double>(), 3.0);
  EXPECT_DOUBLE_EQ(j["cpu_share"].get<double>(), 0.75);
  EXPECT_DOUBLE_EQ(j["load_avg_1m"].get<double>(), 0.25);
  addCpuFields(j, cpuTiming(2.0, 3.0, 2, -1.0));
  EXPECT_TRUE(j["load_avg_1m"].is_null()) << "unknown load";
  EXPECT_EQ(cpuLine(cpuTiming(2.0, 3.0, 2, 0.25)), "cpu 3.00 s (user + sys), share 0.75 of 2 threads, load 0.25 at start");
  EXPECT_EQ(cpuLine(cpuTiming(2.0, 1.0, 1, -1.0)), "cpu 1.00 s (user + sys), share 0.50 of 1 thread");
}

TEST(CpuTime, LoadAverageIsTheFirstFieldOfTheFile) {
  const testing::ScratchDir dir;
  EXPECT_DOUBLE_EQ(loadAverage1m(dir.write("loadavg", "0.42 0.30 0.20 1/123 4567\n").string()), 0.42);
  EXPECT_DOUBLE_EQ(loadAverage1m(dir.write("bad", "busy\n").string()), -1.0);
  EXPECT_DOUBLE_EQ(loadAverage1m((dir / "missing").string()), -1.0);
  EXPECT_GE(loadAverage1m(), 0.0) << "/proc/loadavg on Linux";
}

// A command name holding spaces and ')' does not shift the start time's field; a
// start time past now (or no start time) is unknown.
TEST(CpuTime, ProcessAgeReadsTheStartTimeAfterTheCommandName) {
  const testing::ScratchDir dir;
  std::string fields = "1234 (pen umbra) x) S";
  for (int field = 4; field <= 21; ++field) fields += " 7";
  EXPECT_GT(processAgeSeconds(dir.write("old", fields + " 0 99 100\n").string()), 0.0) << "started at boot";
  EXPECT_DOUBLE_EQ(processAgeSeconds(dir.write("future", fields + " 999999999999 99\n").string()), -1.0);
  EXPECT_DOUBLE_EQ(processAgeSeconds(dir.write("short", "1234 (penumbra) S 1 2\n").string()), -1.0);
  EXPECT_DOUBLE_EQ(processAgeSeconds((dir / "missing").string()), -1.0);
  const double age = processAgeSeconds();
  EXPECT_GT(age, 0.0) << "/proc/self/stat on Linux";
  EXPECT_LT(age, processAgeSeconds("/proc/1/stat")) << "this test started after init";
}

// One thread burns 0.1 s of its own CPU clock: the span sees at least that much CPU,
// and a single busy thread can hold at most its one core of the wall time.
TEST(CpuTime, ASpanOverOneBusyThreadHasAShareOfAtMostOne) {
  auto threadCpu = [] {
    timespec t{};
    clock_gettime(CLOCK_THREAD_CPUTIME_ID, &t);
    return double(t.tv_sec) + 1e-9 * double(t.tv_nsec);
  };
  const CpuSpan span;
  const double start = threadCpu();
  volatile uint64_t x = 1;
  while (threadCpu() - start < 0.1) {
    for (int i = 0; i < 10000; ++i) x = x * 6364136223846793005ull + 1;
  }
  const CpuTiming t = span.timing(1);
  EXPECT_GE(t.cpuSeconds, 0.099);
  EXPECT_GE(t.wallSeconds, 0.099);
  EXPECT_GT(t.share, 0.0);
  EXPECT_LE(t.share, 1.05);
  // Time before the span adds to both clocks.
  const CpuTiming more = span.timing(1, 10.0, 5.0);
  EXPECT_GE(more.wallSeconds, 10.099);
  EXPECT_GE(more.cpuSeconds, 5.099);
}

TEST(BenchArgs, ThreadCountsAreDistinctAndWithinTheCores) {
  EXPECT_EQ(parseThreadCounts("1,2", 2), (std::vector<int>{1, 2}));
  EXPECT_EQ(parseThreadCounts("2,1", 4), (std::vector<int>{2, 1}));
  EXPECT_EQ(parseThreadCounts("3", 4), (std::vector<int>{3}));
  for (const char* bad : {"", "1,", ",1", "1,,2", "x", "1,x", "0", "-1", "1.5", " 1", "1 ", "99999999999"}) {
    EXPECT_THROW(parseThreadCounts(bad, 2), InputError) << "'" << bad << "'";
  }
  try {
    parseThreadCounts("1,4", 2);
    FAIL();
  } catch (const InputError& e) {
    EXPECT_STREQ(e.what(), "--threads: 4 is more than the 2 cores this process may use");
  }
  try {
    parseThreadCounts("2,1,2", 2);
    FAIL();
  } catch (const InputError& e) {
    EXPECT_STREQ(e.what(), "--threads: 2 is given twice");
  }
}

TEST(BenchReport, MinAndMedian) {
  EXPECT_DOUBLE_EQ(minMedian({3, 1, 2}).min, 1);
  EXPECT_DOUBLE_EQ(minMedian({3, 1, 2}).median, 2);
  EXPECT_DOUBLE_EQ(minMedian({4, 1, 3, 2}).median, 2.5);
  EXPECT_DOUBLE_EQ(minMedian({}).median, 0);
}

BenchSample sample(int threads, int round, double total, double render, double cpu) {
  BenchSample s;
  s.threads = threads;
  s.round = round;
  s.time.load = 0.1;
  s.time.render = render;
  s.time.total = total;
  s.cpu = cpuTiming(total, cpu, threads, 0.5);
  return s;
}

// Speed-ups from minima and medians, the control beside the scene, stages nobody
// spent time in left out of the table but kept in the JSON.
TEST(BenchReport, TableAndJsonFromASyntheticOutcome) {
  BenchOutcome o;
  o.threads = {1, 2};
  o.repeat = 3;
  SceneBench s;
  s.path = "scenes/x.json";
  s.name = "x";
  s.settings = "16x16, 1 spp, classic";
  const double totals1[] = {2.0, 2.4, 2.2}, totals2[] = {1.25, 1.0, 1.1};
  for (int r = 0; r < 3; ++r) {
    s.samples.push_back(sample(1, r, totals1[r], totals1[r] - 0.1, totals1[r]));
    s.samples.push_back(sample(2, r, totals2[r], totals2[r] - 0.1, 1.8 * totals2[r]));
    o.control.push_back(sample(1, r, 0.4, 0.0, 0.4));
    o.control.push_back(sample(2, r, 0.25, 0.0, 0.5));
  }
  o.scenes.push_back(s);
  const std::string table = benchTable(o);
  EXPECT_NE(table.find("x (scenes/x.json): 16x16, 1 spp, classic"), std::string::npos) << table;
  EXPECT_NE(table.find("speed-up 2/1 of the total: 2.00x, beside the control's 1.60x"), std::string::npos) << table;
  EXPECT_NE(table.find("\ntotal           2.000    2.200    1.000    1.100     2.00x     2.00x\n"), std::string::npos)
      << table;
  EXPECT_NE(table.find("\ncpu share        1.00     1.00     0.90     0.90\n"), std::string::npos) << table;
  EXPECT_NE(table.find("\ncontrol         0.400    0.400    0.250    0.250     1.60x     1.60x\n"), std::string::npos)
      << table;
  EXPECT_EQ(table.find("\nemit "), std::string::npos) << "no time in it: not in the table";
  const nlohmann::json j = nlohmann::json::parse(benchJson(o));
  EXPECT_DOUBLE_EQ(j["scenes"][0]["stages_s"]["total"]["speedup"]["2/1"]["min"].get<double>(), 2.0);
  EXPECT_DOUBLE_EQ(j["scenes"][0]["stages_s"]["emit"]["1"]["min"].get<double>(), 0.0);
  EXPECT_DOUBLE_EQ(j["control"]["seconds"]["speedup"]["2/1"]["median"].get<double>(), 1.6);
  ASSERT_EQ(j["scenes"][0]["runs"].size(), 6u);
  EXPECT_EQ(j["scenes"][0]["runs"][1]["threads"], 2);
  EXPECT_DOUBLE_EQ(j["scenes"][0]["runs"][1]["cpu_share"].get<double>(), 0.9);
}

}  // namespace
}  // namespace penumbra
