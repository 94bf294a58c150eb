// Running the penumbra binary from a test: a scratch directory, shell quoting, and
// the exit code, stdout and stderr of one command line.
#pragma once
#include <fcntl.h>
#include <sys/wait.h>
#include <unistd.h>
#include <cstdlib>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>
#include <vector>
#include "support/scratch_dir.h"

extern char** environ;

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

// Runs a shell line (its own redirections and environment settings included) and
// returns the exit code, stdout and stderr.
inline CliResult runShell(const std::string& line) {
  const ScratchDir io;
  const std::string cmd = line + " >" + quote((io / "stdout").string()) + " 2>" + quote((io / "stderr").string());
  const int status = std::system(cmd.c_str());
  CliResult r;
  r.exitCode = WIFEXITED(status) ? WEXITSTATUS(status) : -1;
  r.out = readFile(io / "stdout");
  r.err = readFile(io / "stderr");
  return r;
}

// `args` are already shell-quoted.
inline CliResult runCli(const std::string& args) {
  return runShell(quote(PENUMBRA_BINARY) + " " + args + " </dev/null");
}

// Runs the binary on `args` (unquoted, no shell) with PENUMBRA_TEST_SIGNAL_AT=`at`
// (io/temp_file.cpp's test hook: SIGINT at a named point, no polling) and stderr to
// /dev/null; returns the wait status. Everything exec needs is built before the fork.
inline int runCliSignalledAt(const std::string& at, const std::vector<std::string>& args) {
  std::vector<std::string> envText;
  for (char** e = environ; *e; ++e) {
    if (std::strncmp(*e, "PENUMBRA_TEST_SIGNAL_AT=", 24) != 0) envText.emplace_back(*e);
  }
  envText.push_back("PENUMBRA_TEST_SIGNAL_AT=" + at);
  std::vector<char*> env, argv = {const_cast<char*>(PENUMBRA_BINARY)};
  for (std::string& e : envText) env.push_back(e.data());
  env.push_back(nullptr);
  std::vector<std::string> argText = args;
  for (std::string& a : argText) argv.push_back(a.data());
  argv.push_back(nullptr);
  const pid_t child = fork();
  if (child < 0) return -1;
  if (child == 0) {
    const int null = ::open("/dev/null", O_WRONLY);
    if (null >= 0) ::dup2(null, 2);
    ::execve(PENUMBRA_BINARY, argv.data(), env.data());
    _exit(127);
  }
  int status = 0;
  waitpid(child, &status, 0);
  return status;
}

}  // namespace penumbra::testing
