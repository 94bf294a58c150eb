// Loads the image modules with dlopen on first use: the executable has no link-time
// dependency on an image library, so its start-up never pays for loading one.
#include "core/image_codec.h"

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

// The object module `name` returns from its symbol `entry`; `buildPath` is where the
// build put it, for executables run from elsewhere.
template <class T>
const T* load(const char* name, const char* entry, const char* buildPath) {
  using Entry = const T* (*)();
  // Already in the process: an executable (a test, a fuzzer) that links the module.
  if (void* symbol = ::dlsym(RTLD_DEFAULT, entry)) return reinterpret_cast<Entry>(symbol)();
  std::string errors;
  std::vector<std::string> candidates = {executableDir() + "/" + name};
  if (buildPath) candidates.push_back(buildPath);
  for (const std::string& path : candidates) {
    void* module = ::dlopen(path.c_str(), RTLD_NOW | RTLD_LOCAL);
    if (!module) {
      errors += std::string(errors.empty() ? "" : "; ") + ::dlerror();
      continue;
    }
    if (void* symbol = ::dlsym(module, entry)) return reinterpret_cast<Entry>(symbol)();
    errors += std::string(errors.empty() ? "" : "; ") + path + " has no " + entry;
  }
  throw std::runtime_error(std::string("cannot load the image module ") + name + ": " + errors);
}

#ifndef PENUMBRA_IMAGE_MODULE
#define PENUMBRA_IMAGE_MODULE nullptr
#endif
#ifndef PENUMBRA_ENCODER_MODULE
#define PENUMBRA_ENCODER_MODULE nullptr
#endif

}  // namespace

const ImageCodec& imageCodec() {
  static const ImageCodec* const codec = load<ImageCodec>(kImageModuleName, kImageCodecEntry, PENUMBRA_IMAGE_MODULE);
  return *codec;
}

const ImageEncoder& imageEncoder() {
  static const ImageEncoder* const encoder =
      load<ImageEncoder>(kImageEncoderModuleName, kImageEncoderEntry, PENUMBRA_ENCODER_MODULE);
  return *encoder;
}

}  // namespace penumbra
