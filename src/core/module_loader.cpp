// Finds a module (and a helper executable) beside the executable or where the build put it.
#include "core/module_loader.h"

#include <dlfcn.h>
#include <unistd.h>

#include <stdexcept>
#include <string>
#include <vector>

namespace penumbra {
namespace {

std::string executableDir() {
  std::string buf(4096, '\0');
  const ssize_t n = ::readlink("/proc/self/exe", buf.data(), buf.size() - 1);
  if (n <= 0) return "";
  buf.resize(size_t(n));
  return buf.substr(0, buf.rfind('/'));
}

}  // namespace

void* moduleSymbol(const char* name, const char* entry, const char* buildPath, const char* what) {
  // Already in the process: an executable (a test, a fuzzer) that links the module.
  if (void* symbol = ::dlsym(RTLD_DEFAULT, entry)) return symbol;
  std::string errors;
  std::vector<std::string> candidates = {executableDir() + "/" + name};
  if (buildPath) candidates.push_back(buildPath);
  for (const std::string& path : candidates) {
    void* module = ::dlopen(path.c_str(), RTLD_NOW | RTLD_LOCAL);
    if (!module) {
      errors += std::string(errors.empty() ? "" : "; ") + ::dlerror();
      continue;
    }
    if (void* symbol = ::dlsym(module, entry)) return symbol;
    errors += std::string(errors.empty() ? "" : "; ") + path + " has no " + entry;
  }
  throw std::runtime_error(std::string("cannot load the ") + what + " module " + name + ": " + errors);
}

std::string helperExecutable(const char* name, const char* buildPath) {
  for (const std::string& path : {executableDir() + "/" + name, std::string(buildPath ? buildPath : "")}) {
    if (!path.empty() && ::access(path.c_str(), X_OK) == 0) return path;
  }
  return "";
}

}  // namespace penumbra
