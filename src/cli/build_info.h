// What `penumbra --version` names besides the version: the commit the binary was built
// from and how it was built. Defined in a file generated at build time
// (cmake/build_info.cmake), which only the binary's main links, so a new commit
// recompiles that one file.
#pragma once

namespace penumbra {

// The short hash of HEAD, with "-dirty" when tracked files differed from it, or
// "unknown" when the source was not a git checkout.
const char* buildCommit();
// CMAKE_BUILD_TYPE, plus the sanitizers or fuzzing instrumentation when built with them.
const char* buildType();

}  // namespace penumbra
