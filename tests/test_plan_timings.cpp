// CPU time beside wall time, from figures given rather than measured where a
// measurement would race: the share and the contended note, the load average read
// from a file, a span over CPU work counted by the thread's own CPU clock.
#include "core/cpu_time.h"
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

}  // namespace
}  // namespace penumbra
