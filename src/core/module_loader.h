// Shared modules loaded with dlopen on first use (the image codecs, the OpenVDB reader):
// the executable has no link-time dependency on their libraries, so start-up never pays
// for loading them.
#pragma once
#include <string>

namespace penumbra {

// The function `entry` of the module `name`: found in the process when an executable
// links the module, else beside the executable, else at `buildPath` (where the build put
// it, for executables run from elsewhere). The caller casts it to the entry's own type
// (calling through another type is undefined). Throws std::runtime_error "cannot load
// the <what> module NAME: why".
void* moduleSymbol(const char* name, const char* entry, const char* buildPath, const char* what);

// A helper executable `name`: beside the executable, else `buildPath`; "" when neither
// is an executable file.
std::string helperExecutable(const char* name, const char* buildPath);

// The object a module's entry `const T* entry()` returns.
template <class T>
const T* moduleObject(const char* name, const char* entry, const char* buildPath, const char* what) {
  return reinterpret_cast<const T* (*)()>(moduleSymbol(name, entry, buildPath, what))();
}

}  // namespace penumbra
