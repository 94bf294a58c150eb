// penumbra bench's harness without rendering: the thread list, min and median, and
// the table and JSON from a synthetic outcome.
#include "cli/bench/bench_report.h"
#include "cli/bench/bench_run.h"
#include "core/cpu_time.h"
#include "core/error.h"
#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

namespace penumbra {
namespace {

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
