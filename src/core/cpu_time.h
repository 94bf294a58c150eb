// CPU time beside wall time: the process's user + system seconds over a span, its
// share of (wall x threads), and the load average when the span began. What tells
// a slow render from a busy machine.
#pragma once
#include <chrono>
#include <string>

namespace penumbra {

// Below this share of (wall x threads) the span's times are contended: other work
// (or a serial stage) kept the workers off their cores part of the time.
constexpr double kContendedShare = 0.9;
// Spans shorter than this are not judged: waking the workers and the serial set-up
// of a tiny render keep its share low on any machine.
constexpr double kShortestJudgedSeconds = 0.5;

struct CpuTiming {
  double wallSeconds = 0.0;
  double cpuSeconds = 0.0;   // user + system, the whole process
  double share = 0.0;        // cpuSeconds / (wallSeconds x threads)
  int threads = 1;
  double loadAverage = -1.0;  // 1-minute load average at the span's start; < 0 unknown

  bool known() const { return wallSeconds > 0.0; }
  bool contended() const { return wallSeconds >= kShortestJudgedSeconds && share < kContendedShare; }
};

// `cpu` seconds over `wall` seconds on `threads` workers, the span started at `load`.
CpuTiming cpuTiming(double wall, double cpu, int threads, double load);

// User + system seconds this process has used so far (getrusage, every thread).
double processCpuSeconds();

// Wall seconds since this process started, its loading and static set-up included
// (Linux: /proc/self/stat's start time against the boot clock); -1 when unknown.
double processAgeSeconds(const std::string& statPath = "/proc/self/stat");

// The 1-minute load average, the first field of `path` (/proc/loadavg); -1 when it
// cannot be read.
double loadAverage1m(const std::string& path = "/proc/loadavg");

// Wall clock, process CPU clock and the load average, all read at construction.
class CpuSpan {
 public:
  CpuSpan();
  double wallSeconds() const;
  double cpuSeconds() const;
  double loadAtStart() const { return load_; }
  // The span so far on `threads` workers; `wall` and `cpu` add time spent before it
  // (a stage shared with earlier work) to the same account.
  CpuTiming timing(int threads, double wall = 0.0, double cpu = 0.0) const;

 private:
  std::chrono::steady_clock::time_point wall0_;
  double cpu0_ = 0.0;
  double load_ = -1.0;
};

}  // namespace penumbra
