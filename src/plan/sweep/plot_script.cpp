// posix_spawn of the plotting script and its exit status.
#include "plan/sweep/plot_script.h"
#include <fmt/format.h>
#include <filesystem>
#include <spawn.h>
#include <sys/wait.h>
#include <vector>

extern char** environ;

namespace penumbra {
namespace {

// Exit status of a program run with these arguments (no shell), 127 if it could not start.
int runProgram(const std::vector<std::string>& args) {
  std::vector<char*> argv;
  for (const std::string& a : args) argv.push_back(const_cast<char*>(a.c_str()));
  argv.push_back(nullptr);
  pid_t pid = 0;
  if (posix_spawnp(&pid, argv[0], nullptr, nullptr, argv.data(), environ) != 0) return 127;
  int status = 0;
  if (waitpid(pid, &status, 0) < 0) return 127;
  return WIFEXITED(status) ? WEXITSTATUS(status) : 128 + WTERMSIG(status);
}

}  // namespace

std::string drawTradeoffPlot(const std::string& script, const std::string& csv, const std::string& png,
                             const std::string& title, const std::string& metric, const std::string& cost) {
  // Debian's interpreter first: python3-matplotlib (make deps) is installed for it,
  // and a python3 earlier on PATH (pyenv, a venv) may not have it.
  const std::string python = std::filesystem::exists("/usr/bin/python3") ? "/usr/bin/python3" : "python3";
  const int status = runProgram({python, script, csv, png, "--title", title, "--metric", metric, "--cost", cost});
  if (status == 0) return "";
  // The script's exit codes: 2 = nothing it can plot (its line above says why),
  // 3 = matplotlib missing; anything else is its own failure.
  if (status == 2) return fmt::format("{} not drawn: nothing to plot (the line above says why)", png);
  if (status == 3) return fmt::format("{} not drawn: python3-matplotlib is missing (make deps installs it)", png);
  return fmt::format("{} not drawn: {} {} exited with {}", png, python, script, status);
}

}  // namespace penumbra
