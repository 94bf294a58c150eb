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
#include "support/scratch_dir.h"

namespace penumbra::testing {

namespace fs = std::filesystem;

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
