// Why an input file cannot be read, said in words a user can act on: a path too long
// for the system is not a missing file.
#pragma once
#include <string>

namespace penumbra {

// "" when `path` names a readable regular file; else the reason ("does not exist",
// "is a directory", "its path is longer than PATH_MAX (4096 bytes)", ...).
std::string unreadableFileReason(const std::string& path);

}  // namespace penumbra
