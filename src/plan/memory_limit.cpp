// Memory limits. Available memory is read at check time rather than total RAM:
// other jobs on the machine count, and a render that starts swapping (or, with no
// swap, is killed) after minutes is worse than one refused up front.
#include "plan/memory_limit.h"
#include "plan/cost_model.h"
#include "core/error.h"
#include <unistd.h>
#include <cctype>
#include <cmath>
#include <cstdlib>
#include <fstream>
#include <sstream>

namespace penumbra {
namespace {

// Resident set size now (not the peak): /proc/self/statm's second field, in pages.
uint64_t currentRssBytes() {
  std::ifstream statm("/proc/self/statm");
  uint64_t size = 0, resident = 0;
  if (!(statm >> size >> resident)) return 0;
  return resident * static_cast<uint64_t>(::sysconf(_SC_PAGESIZE));
}

}  // namespace

uint64_t parseMemorySize(const std::string& text, const std::string& option) {
  auto bad = [&]() -> uint64_t {
    throw InputError(option + ": expected a size like 8G, 512M or 1.5GiB, got '" + text + "'");
  };
  const char* begin = text.c_str();
  char* end = nullptr;
  const double value = std::strtod(begin, &end);
  if (end == begin || !std::isfinite(value) || !(value > 0.0)) return bad();
  std::string unit;
  for (const char* c = end; *c; ++c) unit += static_cast<char>(std::tolower(static_cast<unsigned char>(*c)));
  double scale = 0.0;
  if (unit.empty() || unit == "b") scale = 1.0;
  else if (unit == "k" || unit == "kb" || unit == "kib") scale = 1024.0;
  else if (unit == "m" || unit == "mb" || unit == "mib") scale = 1024.0 * 1024;
  else if (unit == "g" || unit == "gb" || unit == "gib") scale = 1024.0 * 1024 * 1024;
  else if (unit == "t" || unit == "tb" || unit == "tib") scale = 1024.0 * 1024 * 1024 * 1024;
  else return bad();
  const double bytes = value * scale;
  if (bytes < 1.0 || bytes > 1.8e19) return bad();
  return static_cast<uint64_t>(bytes);
}

uint64_t availableMemoryBytes() {
  std::ifstream meminfo("/proc/meminfo");
  std::string line;
  while (std::getline(meminfo, line)) {
    std::istringstream in(line);
    std::string key;
    uint64_t kib = 0;
    if (in >> key >> kib && key == "MemAvailable:") return kib * 1024 + currentRssBytes();
  }
  const long pages = ::sysconf(_SC_AVPHYS_PAGES), page = ::sysconf(_SC_PAGESIZE);
  return pages > 0 && page > 0 ? uint64_t(pages) * uint64_t(page) + currentRssBytes() : 0;
}

MemoryLimit memoryLimit(uint64_t requested) {
  if (requested > 0) return {requested, "--max-memory"};
  return {availableMemoryBytes(), "available memory"};
}

LoadLimits loadLimits(uint64_t requested) {
  const MemoryLimit limit = memoryLimit(requested);
  return {limit.bytes, limit.name, static_cast<uint64_t>(cost::kBaseBytes)};
}

void checkMemory(const ResourceEstimate& estimate, const MemoryLimit& limit,
                 const std::string& sceneFile) {
  if (limit.bytes == 0 || estimate.totalBytes() <= double(limit.bytes)) return;
  throw InputError(sceneFile + ": needs " + describeMemory(estimate) + " but " + limit.name + " is " +
                   formatBytes(double(limit.bytes)));
}

}  // namespace penumbra
