// Process-level measurements for the stats report.
#include "core/stats.h"
#include <fstream>
#include <string>

namespace penumbra {

uint64_t peakRssBytes() {
  std::ifstream status("/proc/self/status");
  std::string line;
  while (std::getline(status, line)) {
    if (line.rfind("VmHWM:", 0) == 0) return std::stoull(line.substr(6)) * 1024;  // kB
  }
  return 0;
}

}  // namespace penumbra
