// Shared modules loaded with dlopen on first use (the image codecs, the OpenVDB reader):
// the executable has no link-time dependency on their libraries, so start-up never pays
// for loading them.
#pragma once

namespace penumbra {

// The object the module `name` returns from its symbol `entry`: found in the process
// when an executable links the module, else beside the executable, else at `buildPath`
// (where the build put it, for executables run from elsewhere). Throws
// std::runtime_error "cannot load the <what> module NAME: why".
const void* moduleEntry(const char* name, const char* entry, const char* buildPath, const char* what);

}  // namespace penumbra
