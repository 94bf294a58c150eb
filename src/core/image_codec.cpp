// Loads the image module with dlopen on first use: the executable has no link-time
// dependency on the image library, so its start-up never pays for loading it.
#include "core/image_codec.h"

#include <dlfcn.h>
#include <unistd.h>

#include <stdexcept>
#include <string>
#include <vector>

namespace penumbra {
namespace {

using Entry = const ImageCodec* (*)();

std::string executableDir() {
  std::string buf(4096, '\0');
  const ssize_t n = ::readlink("/proc/self/exe", buf.data(), buf.size() - 1);
  if (n <= 0) return "";
  buf.resize(size_t(n));
  return buf.substr(0, buf.rfind('/'));
}

const ImageCodec* load() {
  // Already in the process: an executable (a test, a fuzzer) that links the module.
  if (void* entry = ::dlsym(RTLD_DEFAULT, kImageCodecEntry)) return reinterpret_cast<Entry>(entry)();
  std::string errors;
  std::vector<std::string> candidates = {executableDir() + "/" + kImageModuleName};
#ifdef PENUMBRA_IMAGE_MODULE
  candidates.push_back(PENUMBRA_IMAGE_MODULE);  // the build folder's, for executables run from elsewhere
#endif
  for (const std::string& path : candidates) {
    void* module = ::dlopen(path.c_str(), RTLD_NOW | RTLD_LOCAL);
    if (!module) {
      errors += std::string(errors.empty() ? "" : "; ") + ::dlerror();
      continue;
    }
    if (void* entry = ::dlsym(module, kImageCodecEntry)) return reinterpret_cast<Entry>(entry)();
    errors += std::string(errors.empty() ? "" : "; ") + path + " has no " + kImageCodecEntry;
  }
  throw std::runtime_error(std::string("cannot load the image module ") + kImageModuleName + ": " + errors);
}

}  // namespace

const ImageCodec& imageCodec() {
  static const ImageCodec* const codec = load();
  return *codec;
}

}  // namespace penumbra
