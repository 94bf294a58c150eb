// Process CPU time (getrusage), the process's age (/proc/self/stat) and the load
// average (/proc/loadavg).
#include "core/cpu_time.h"
#include <sys/resource.h>
#include <unistd.h>
#include <ctime>
#include <fstream>
#include <iterator>
#include <sstream>

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

double processAgeSeconds(const std::string& statPath) {
  std::ifstream in(statPath);
  std::string stat((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
  // Field 2 (the command name) may hold spaces and ')': the fields after it count
  // from its last ')'. The start time is field 22, in clock ticks since boot.
  const size_t close = stat.rfind(')');
  if (close == std::string::npos) return -1.0;
  std::istringstream fields(stat.substr(close + 1));
  std::string field;
  for (int i = 3; i < 22; ++i) fields >> field;
  unsigned long long ticks = 0;
  const long hz = sysconf(_SC_CLK_TCK);
  timespec now{};
  if (!(fields >> ticks) || hz <= 0 || clock_gettime(CLOCK_BOOTTIME, &now) != 0) return -1.0;
  const double age = double(now.tv_sec) + 1e-9 * double(now.tv_nsec) - double(ticks) / double(hz);
  return age >= 0.0 ? age : -1.0;
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
