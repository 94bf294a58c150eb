// Process CPU time (getrusage) and the load average (/proc/loadavg).
#include "core/cpu_time.h"
#include <sys/resource.h>
#include <fstream>

namespace penumbra {

CpuTiming cpuTiming(double wall, double cpu, int threads, double load) {
  CpuTiming t;
  t.wallSeconds = wall;
  t.cpuSeconds = cpu;
  t.threads = threads > 0 ? threads : 1;
  t.share = wall > 0.0 ? cpu / (wall * t.threads) : 0.0;
  t.loadAverage = load;
  return t;
}

double processCpuSeconds() {
  rusage u{};
  if (getrusage(RUSAGE_SELF, &u) != 0) return 0.0;
  return double(u.ru_utime.tv_sec + u.ru_stime.tv_sec) + 1e-6 * double(u.ru_utime.tv_usec + u.ru_stime.tv_usec);
}

double loadAverage1m(const std::string& path) {
  std::ifstream in(path);
  double load = -1.0;
  if (!(in >> load) || load < 0.0) return -1.0;
  return load;
}

CpuSpan::CpuSpan() : wall0_(std::chrono::steady_clock::now()), cpu0_(processCpuSeconds()), load_(loadAverage1m()) {}

double CpuSpan::wallSeconds() const {
  return std::chrono::duration<double>(std::chrono::steady_clock::now() - wall0_).count();
}

double CpuSpan::cpuSeconds() const { return processCpuSeconds() - cpu0_; }

CpuTiming CpuSpan::timing(int threads, double wall, double cpu) const {
  // CPU first: the wall clock then covers at least the CPU reading's span.
  const double used = cpuSeconds();
  return cpuTiming(wall + wallSeconds(), cpu + used, threads, load_);
}

}  // namespace penumbra
