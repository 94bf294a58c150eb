// A scratch folder under the system temp directory, removed with everything in it
// when the object goes out of scope: also when an ASSERT returns early or a test
// throws, which a remove_all at the end of a test body would skip.
#pragma once
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <string>
#include <system_error>
#include <unistd.h>

namespace penumbra::testing {

namespace fs = std::filesystem;

class ScratchDir {
 public:
  ScratchDir() {
    std::string pattern = (fs::temp_directory_path() / "penumbra-test-XXXXXX").string();
    if (!mkdtemp(pattern.data())) std::abort();
    path_ = pattern;
  }
  ~ScratchDir() {
    std::error_code ec;
    fs::permissions(path_, fs::perms::owner_all, fs::perm_options::add, ec);
    fs::remove_all(path_, ec);
  }
  fs::path write(const std::string& name, const std::string& text) const {
    std::ofstream(path_ / name, std::ios::binary) << text;
    return path_ / name;
  }
  fs::path operator/(const std::string& name) const { return path_ / name; }
  const fs::path& path() const { return path_; }
  // Names of entries containing ".tmp": what an interrupted write would leave.
  int tempFiles() const {
    int n = 0;
    for (const auto& e : fs::directory_iterator(path_)) n += e.path().filename().string().find(".tmp") != std::string::npos;
    return n;
  }

 private:
  fs::path path_;
};

}  // namespace penumbra::testing
