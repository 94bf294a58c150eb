// How a job's scene is loaded from the options every job shares.
#include "plan/session_options.h"
#include "plan/memory_limit.h"

namespace penumbra {

std::vector<std::string> jobOverrides(const SessionOptions& options, const std::vector<std::string>& own) {
  std::vector<std::string> all = options.overrides;
  all.insert(all.end(), own.begin(), own.end());
  return all;
}

Scene loadJobScene(const std::string& path, const SessionOptions& options, const std::vector<std::string>& own) {
  return loadScene(path, jobOverrides(options, own), loadLimits(options.maxMemoryBytes), options.load);
}

}  // namespace penumbra
