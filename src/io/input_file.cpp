// The reasons come from stat(2) and access(2): ENAMETOOLONG is told apart from ENOENT,
// since a path past PATH_MAX, or a name past NAME_MAX, may name a file that exists.
#include "io/input_file.h"
#include <fmt/format.h>
#include <sys/stat.h>
#include <unistd.h>
#include <cerrno>
#include <climits>
#include <cstring>

namespace penumbra {

std::string unreadableFileReason(const std::string& path) {
  if (path.empty()) return "the path is empty";
  struct stat st;
  if (::stat(path.c_str(), &st) != 0) {
    switch (errno) {
      case ENOENT: return "does not exist";
      case ENOTDIR: return "a folder on its path is a file";
      case ENAMETOOLONG:
        return path.size() >= PATH_MAX
                   ? fmt::format("its path is {} bytes, longer than the system allows (PATH_MAX {})", path.size(), PATH_MAX)
                   : fmt::format("a name on its path is longer than the system allows (NAME_MAX {})", NAME_MAX);
      default: return std::strerror(errno);
    }
  }
  if (S_ISDIR(st.st_mode)) return "is a folder, not a file";
  if (!S_ISREG(st.st_mode)) return "is not a regular file";
  if (::access(path.c_str(), R_OK) != 0) return std::string("cannot be read: ") + std::strerror(errno);
  return "";
}

}  // namespace penumbra
