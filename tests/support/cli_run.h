// Running the penumbra binary from a test: a scratch directory, shell quoting, and
// the exit code, stdout and stderr of one command line.
#pragma once
#include <sys/wait.h>
#include <unistd.h>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>

namespace penumbra::testing {

namespace fs = std::filesystem;

class ScratchDir {
 public:
  ScratchDir() {
    std::string pattern = (fs::temp_directory_path() / "penumbra-cli-XXXXXX").string();
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

inline std::string readFile(const fs::path& p) {
  std::ifstream in(p, std::ios::binary);
  std::ostringstream s;
  s << in.rdbuf();
  return s.str();
}

inline std::string quote(const std::string& s) { return "'" + s + "'"; }

struct CliResult {
  int exitCode = -1;
  std::string out, err;
};

// `args` are already shell-quoted; output goes to files outside `dir` listings' way.
inline CliResult runCli(const std::string& args) {
  const ScratchDir io;
  const fs::path out = io / "stdout", err = io / "stderr";
  const std::string cmd = quote(PENUMBRA_BINARY) + " " + args + " >" + quote(out.string()) + " 2>" +
                          quote(err.string()) + " </dev/null";
  const int status = std::system(cmd.c_str());
  CliResult r;
  r.exitCode = WIFEXITED(status) ? WEXITSTATUS(status) : -1;
  r.out = readFile(out);
  r.err = readFile(err);
  return r;
}

}  // namespace penumbra::testing
